// A species file with its barbule outline's width replaced, for benchmarks on segments of a
// chosen width (bench bem, the approximate solver's accuracy ladder).
#pragma once

#include <filesystem>
#include <string>

namespace plumage::cli {

// Writes a temporary copy of `file` with structure.outline.width_um = width_um and corner_um =
// min(1, width_um/10) (narrow segments keep their corners inside the outline); the caller removes
// it after loading. Throws UsageError (prefixed with `who`) if the file cannot be read or has no
// structure.outline.
std::filesystem::path segment_config(const std::string& file, double width_um, const std::string& who);

}  // namespace plumage::cli
