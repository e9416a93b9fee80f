// The characterisation overrides (plumage/characterize_settings.hpp: --grid, --lambda-nm,
// --instances, ...) as flags, shared by `plumage characterize` and `plumage materials`: one flag
// per row of the library's table, read back through the table (its ranges and messages).
#pragma once

#include <map>
#include <string>

#include <CLI/CLI.hpp>

#include "plumage/characterize_settings.hpp"

namespace plumage::cli {

// Flag values by parameter name (as typed; "" = not given).
using OverrideFlags = std::map<std::string, std::string>;

void add_characterize_override_flags(CLI::App& cmd, OverrideFlags& flags);
CharacterizeOverrides read_characterize_overrides(const OverrideFlags& flags);

}  // namespace plumage::cli
