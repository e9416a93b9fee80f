// Builder sections of a crystal cell against the registered table builders (table_builder.hpp).
#include "plumage/table_builder.hpp"

#include "plumage/plugin_registry.hpp"

namespace plumage {

std::vector<std::string> check_builder_sections(const CrystalCell& cell, const PluginRegistry& registry) {
  std::vector<std::string> checked;
  const std::vector<std::string> types = registry.types_of_kind(TableBuilder::plugin_kind);
  for (const auto& [name, section] : cell.builder_sections) {
    if (!registry.find(TableBuilder::plugin_kind, name)) {
      std::string message = "no table_builder '" + name + "' is registered";
      if (auto near = nearest_name(name, types)) message += " (did you mean '" + *near + "'?)";
      std::string all;
      for (const auto& t : types) all += (all.empty() ? "" : ", ") + t;
      message += all.empty() ? "; no table builder is loaded" : "; registered: " + all;
      message += " (a map in a crystal cell is the section of the table builder of that name)";
      throw ConfigError(section.mark(), section.path(), message);
    }
    registry.create_named<TableBuilder>(name, ParamView{}, registry.context())->check_cell(cell);
    checked.push_back(name);
  }
  return checked;
}

}  // namespace plumage
