// Where plumage finds its shipped data (CIE tables, plotting scripts).
#pragma once

#include <filesystem>

namespace plumage {

// $PLUMAGE_DATA_DIR, else <folder of libplumage_core.so>/../share/plumage (right also in a
// program that is not ours, e.g. python3 importing the package), else <folder of the
// executable>/../share/plumage, else the install prefix's share/plumage, else the source tree's
// data folder. Throws Error naming every place it looked.
std::filesystem::path data_directory();

// Absolute path of the running executable (from /proc/self/exe).
std::filesystem::path executable_path();

// Absolute path of the loaded libplumage_core.so (dladdr); empty if it cannot be told. The build
// tree mirrors the install tree, so its folder locates the plug-ins and the data of a process
// whose executable is not plumage's (the Python package).
std::filesystem::path core_library_path();

}  // namespace plumage
