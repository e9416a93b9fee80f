// The inputs of a species variant's materials (material_key.hpp).
#include "plumage/material_key.hpp"

#include <fstream>
#include <iterator>
#include <sstream>

#include "plumage/config_document.hpp"
#include "plumage/input_file.hpp"
#include "plumage/local_reflection.hpp"
#include "plumage/scattering_solver.hpp"
#include "plumage/structure_generator.hpp"
#include "yaml_state.hpp"

namespace plumage {

namespace fs = std::filesystem;

namespace {

// Files named inside a file named inside a file ...: deeper chains are not followed.
constexpr int kMaxFileDepth = 8;

std::string file_digest(const fs::path& file, int depth);

// Every scalar of `node` (values and list items, not keys) that names an existing regular file
// relative to `dir` (or absolutely), with its dotted path, in document order.
void referenced_files(const YAML::Node& node, const std::string& path, const fs::path& dir, int depth,
                      std::vector<MaterialInputs::File>& out) {
  if (!node) return;
  if (node.IsScalar()) {
    const std::string& text = node.Scalar();
    if (text.empty() || text.size() > 4096) return;
    std::error_code ec;
    const fs::path p = fs::path(text).is_absolute() ? fs::path(text) : dir / text;
    if (fs::is_regular_file(p, ec)) out.push_back({path, file_digest(p, depth + 1)});
  } else if (node.IsSequence()) {
    std::size_t k = 0;
    for (const auto& item : node) referenced_files(item, path + "[" + std::to_string(k++) + "]", dir, depth, out);
  } else if (node.IsMap()) {
    for (auto it = node.begin(); it != node.end(); ++it)
      referenced_files(it->second, path.empty() ? it->first.Scalar() : path + "." + it->first.Scalar(), dir, depth, out);
  }
}

// A YAML file by its canonical text and the files it names; any other file by its bytes.
std::string file_digest(const fs::path& file, int depth) {
  const auto ext = file.extension().string();
  if ((ext == ".yaml" || ext == ".yml") && depth <= kMaxFileDepth) {
    const ConfigDocument doc = ConfigDocument::load(file);
    std::string text = canonical_text(doc.root());
    std::vector<MaterialInputs::File> nested;
    referenced_files(doc.root().state()->node, "", doc.directory(), depth, nested);
    for (const auto& f : nested) text += "\nfile " + f.where + " " + f.digest;
    return fnv1a_hex(text);
  }
  return fnv1a_hex(read_input_file(file, "file named by a species config"));
}

// The merged variant without the bookkeeping of variants (the variant name is in the label).
YAML::Node variant_tree(const SpeciesConfig& config) {
  YAML::Node tree = YAML::Clone(config.root.state()->node);
  tree.remove("variants");
  tree.remove("variant");
  return tree;
}

void add_model(const PluginRegistry& registry, std::string_view kind, const std::string& type,
               std::vector<MaterialInputs::Model>& out) {
  if (type.empty()) return;
  const auto* entry = registry.find(kind, type);
  out.push_back({std::string(kind), type, entry ? entry->info.version : std::string("unregistered")});
}

std::string type_of(const ParamView& root, const char* section, const char* key) {
  if (!root.has(section) || !root.node(section).is_map()) return {};
  return root.child(section).text_or(key, "");
}

}  // namespace

std::string MaterialInputs::text() const {
  std::ostringstream o;
  o << "species " << species << "\n";
  for (const File& f : files) o << "file " << f.where << " " << f.digest << "\n";
  for (const Model& m : models) o << "model " << m.kind << " " << m.type << " " << m.version << "\n";
  return o.str();
}

MaterialInputs material_inputs(const SpeciesConfig& config, const PluginRegistry& registry) {
  MaterialInputs in;
  const YAML::Node tree = variant_tree(config);
  in.species = fnv1a_hex(canonical_text(make_root_view(tree, config.file.string())));
  referenced_files(tree, "", config.directory, 0, in.files);
  add_model(registry, StructureGenerator::plugin_kind, type_of(config.root, "structure", "generator"), in.models);
  add_model(registry, LocalReflection::plugin_kind, type_of(config.root, "reflection", "model"), in.models);
  add_model(registry, ScatteringSolver::plugin_kind, config.solver_type, in.models);
  return in;
}

std::string config_digest(const std::string& inputs_text) {
  std::istringstream lines(inputs_text);
  std::string identity;
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("species ", 0) == 0 || line.rfind("file ", 0) == 0) identity += line + "\n";
  return fnv1a_hex(identity);
}

}  // namespace plumage
