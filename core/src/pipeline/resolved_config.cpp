// resolved_config_yaml (plumage/config_check.hpp): `plumage check --resolved`. Every declaration a
// loader read notes its row on the view it read from (ParamView::note, from ParamTable::read_into);
// this walks the views of a loaded configuration beside its YAML tree and writes the tree with
// the absent parameters filled in at their defaults, each parameter's unit, range and doc as a
// comment.
#include <yaml-cpp/yaml.h>

#include <cctype>
#include <sstream>

#include "plumage/config_check.hpp"
#include "plumage/config_document.hpp"
#include "plumage/species_config.hpp"
#include "yaml_state.hpp"

namespace plumage {

namespace {

std::string describe(const ParamSpec& spec, bool defaulted) {
  std::string out = defaulted ? "default" : "";
  auto add = [&out](const std::string& part) {
    if (part.empty()) return;
    out += (out.empty() ? "" : "; ") + part;
  };
  if (!spec.unit.empty() && spec.unit != "-" && spec.unit != "1") add(spec.unit);
  if (!spec.range.empty()) add(spec.range);
  add(spec.meaning);
  return out;
}

// A default that is a value (a number, a switch, an interval or list, "", a word of a choice or
// text), not a description such as "the preset's".
bool is_value(const ParamSpec& spec) {
  const std::string& text = spec.default_value;
  if (text.empty() || text.rfind("required", 0) == 0) return false;
  if (text == "true" || text == "false" || text == "\"\"" || text == "{}") return true;
  if ((spec.type == "choice" || spec.type == "text") && text.find(' ') == std::string::npos) return true;
  const char c = text.front();
  return c == '[' || c == '-' || std::isdigit(static_cast<unsigned char>(c));
}

void emit_default(YAML::Emitter& out, const std::string& key, const ParamSpec& spec) {
  out << YAML::Key << key << YAML::Value;
  if (is_value(spec)) {
    out << YAML::Load(spec.default_value) << YAML::Comment(describe(spec, true));
  } else {
    out << YAML::Null << YAML::Comment("default: " + spec.default_value + "; " + describe(spec, false));
  }
}

const std::pair<ParamSpec, bool>* find_note(const ParamView::State* state, const std::string& key) {
  if (!state) return nullptr;
  for (const auto& note : state->notes)
    if (note.first.name == key) return &note;
  return nullptr;
}

void emit_map(YAML::Emitter& out, const YAML::Node& node, const ParamView::State* state, bool top) {
  out << YAML::BeginMap;
  for (auto it = node.begin(); it != node.end(); ++it) {
    const std::string key = it->first.Scalar();
    if (top && key == "variants") continue;  // merged into the tree already
    const ParamView::State* child = nullptr;
    if (state) {
      auto found = state->child_by_key.find(key);
      if (found != state->child_by_key.end()) child = found->second.get();
    }
    out << YAML::Key << key << YAML::Value;
    const auto* note = find_note(state, key);
    if (it->second.IsMap()) {
      emit_map(out, it->second, child, false);
    } else {
      out << it->second;
      if (note) out << YAML::Comment(describe(note->first, false));
    }
  }
  if (state) {
    for (const auto& [spec, defaulted] : state->notes) {
      if (!defaulted || spec.name.find('.') != std::string::npos || node[spec.name]) continue;
      if (spec.type != "map") {
        emit_default(out, spec.name, spec);
        continue;
      }
      // A section left out: its rows at their defaults (noted as "section.key").
      out << YAML::Key << spec.name << YAML::Value << YAML::BeginMap;
      for (const auto& [sub, sub_defaulted] : state->notes) {
        if (sub.name.rfind(spec.name + ".", 0) == 0 && sub.name.find('.', spec.name.size() + 1) == std::string::npos)
          emit_default(out, sub.name.substr(spec.name.size() + 1), sub);
      }
      out << YAML::EndMap;
    }
  }
  out << YAML::EndMap;
}

}  // namespace

std::string resolved_config_yaml(const std::filesystem::path& file, const PluginRegistry& registry) {
  const ConfigDocument doc = ConfigDocument::load(file);
  std::ostringstream text;
  if (!doc.root().has("species") || doc.root().has("comparison")) {
    YAML::Emitter out;
    emit_map(out, doc.root().state()->node, nullptr, false);
    text << "# " << file.string() << " as written (defaults are filled in for species files)\n" << out.c_str() << "\n";
    return text.str();
  }
  std::vector<std::string> variants = species_variants(file);
  if (variants.empty()) variants.push_back("");
  for (const std::string& v : variants) {
    const SpeciesConfig config = load_species_config(file, registry, v);
    YAML::Node tree = config.root.state()->node;
    if (!v.empty()) tree["variant"] = v;  // the merged tree still names the file's default
    YAML::Emitter out;
    emit_map(out, tree, config.root.state().get(), true);
    text << "--- # " << file.string() << (v.empty() ? "" : ", variant " + v) << ": merged, defaults filled in\n"
         << out.c_str() << "\n";
  }
  return text.str();
}

}  // namespace plumage
