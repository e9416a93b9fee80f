// Where plumage finds its shipped data (CIE tables, plotting scripts).
#pragma once

#include <filesystem>

namespace plumage {

// $PLUMAGE_DATA_DIR, else <folder of the executable>/../share/plumage, else the install prefix's
// share/plumage, else the source tree's data folder. Throws Error naming every place it looked.
std::filesystem::path data_directory();

// Absolute path of the running executable (from /proc/self/exe).
std::filesystem::path executable_path();

}  // namespace plumage
