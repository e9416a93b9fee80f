#include "characterize_flags.hpp"

#include <algorithm>
#include <vector>

#include "param_flags.hpp"
#include "plumage/config_document.hpp"

namespace plumage::cli {

namespace {

std::string flag_of(std::string name) {
  std::replace(name.begin(), name.end(), '_', '-');
  return "--" + name;
}

}  // namespace

void add_characterize_override_flags(CLI::App& cmd, OverrideFlags& flags) {
  for (const ParamSpec& p : characterize_overrides_table().specs())
    cmd.add_option(flag_of(p.name), flags[p.name], p.meaning + " (default: " + p.default_value + ")");
}

CharacterizeOverrides read_characterize_overrides(const OverrideFlags& flags) {
  std::vector<std::string> args;
  for (const auto& [name, value] : flags) {
    if (value.empty()) continue;
    args.push_back(flag_of(name));
    args.push_back(value);
  }
  const auto& table = characterize_overrides_table();
  const ConfigDocument doc = ConfigDocument::parse(flags_to_yaml(table.specs(), args), "command line");
  CharacterizeOverrides overrides = table.read(doc.root());
  doc.root().finish();
  return overrides;
}

}  // namespace plumage::cli
