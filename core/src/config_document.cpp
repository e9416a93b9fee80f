#include "plumage/checksum.hpp"
#include "plumage/config_document.hpp"

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <algorithm>
#include <fstream>
#include <sstream>

#include "yaml_state.hpp"

namespace plumage {

std::string SourceMark::str() const {
  if (line <= 0) return file;
  return file + ":" + std::to_string(line) + ":" + std::to_string(column);
}

ConfigError::ConfigError(SourceMark mark, std::string field, std::string message)
    : Error(mark.str() + ": " + (field.empty() ? std::string() : field + ": ") + message),
      mark_(std::move(mark)),
      field_(std::move(field)),
      message_(std::move(message)) {}

ParamView make_root_view(const YAML::Node& node, const std::string& file) {
  auto state = std::make_shared<ParamView::State>();
  state->node = node;
  state->file = file;
  return ParamView(state);
}

std::string fnv1a_hex(std::string_view bytes) {
  std::uint64_t h = fnv1a(bytes);
  static const char* digits = "0123456789abcdef";
  std::string out(16, '0');
  for (int i = 15; i >= 0; --i) {
    out[i] = digits[h & 0xf];
    h >>= 4;
  }
  return out;
}

ConfigDocument ConfigDocument::parse(const std::string& text, const std::string& name) {
  ConfigDocument doc;
  doc.path_ = name;
  doc.hash_ = fnv1a_hex(text);
  YAML::Node node;
  try {
    node = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw ConfigError({name, e.mark.line + 1, e.mark.column + 1}, "",
                      "YAML syntax error: " + e.msg);
  }
  if (!node.IsMap()) {
    throw ConfigError({name, 1, 1}, "", "expected a map of settings at the top of the file");
  }
  doc.root_ = make_root_view(node, name);
  return doc;
}

ConfigDocument ConfigDocument::load(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    throw ConfigError({file.string(), 0, 0}, "",
                      std::filesystem::exists(file) ? "cannot read file" : "no such file");
  }
  std::ostringstream buffer;
  buffer << in.rdbuf();
  ConfigDocument doc = parse(buffer.str(), file.string());
  doc.path_ = file;
  return doc;
}

namespace {

void canonical(const YAML::Node& n, std::string& out) {
  if (!n || n.IsNull()) {
    out += "~";
  } else if (n.IsScalar()) {
    // Length-prefixed so that no scalar can imitate structure.
    out += std::to_string(n.Scalar().size()) + ":" + n.Scalar();
  } else if (n.IsSequence()) {
    out += "[";
    for (const auto& item : n) {
      canonical(item, out);
      out += ",";
    }
    out += "]";
  } else {
    std::vector<std::pair<std::string, YAML::Node>> entries;
    for (auto it = n.begin(); it != n.end(); ++it) entries.emplace_back(it->first.Scalar(), it->second);
    std::sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    out += "{";
    for (const auto& [key, value] : entries) {
      out += std::to_string(key.size()) + ":" + key + "=";
      canonical(value, out);
      out += ",";
    }
    out += "}";
  }
}

// Copies a node tree keeping every node's mark (YAML::Clone keeps them too, but shares no state
// with the original, which is what a derived document needs).
YAML::Node copy_tree(const YAML::Node& n) { return YAML::Clone(n); }

}  // namespace

std::string canonical_text(const ParamView& view) {
  std::string out;
  canonical(view.state()->node, out);
  return out;
}

ConfigDocument ConfigDocument::derive(const ParamView& base, const std::vector<Override>& overrides,
                                      const std::filesystem::path& directory, const std::string& name) {
  YAML::Node tree = copy_tree(base.state()->node);
  for (const Override& o : overrides) {
    YAML::Node value;
    try {
      value = YAML::Load(o.yaml);
    } catch (const YAML::ParserException& e) {
      throw ConfigError({name, 0, 0}, o.path, "not a YAML value: '" + o.yaml + "' (" + e.msg + ")");
    }
    // Walk to the parent map of the last path component.
    std::vector<std::string> parts;
    for (std::size_t start = 0;;) {
      const std::size_t dot = o.path.find('.', start);
      parts.push_back(o.path.substr(start, dot == std::string::npos ? std::string::npos : dot - start));
      if (dot == std::string::npos) break;
      start = dot + 1;
    }
    YAML::Node parent = tree;
    std::string walked;
    for (std::size_t k = 0; k + 1 < parts.size(); ++k) {
      walked += (walked.empty() ? "" : ".") + parts[k];
      YAML::Node next = parent[parts[k]];
      if (!next || next.IsNull()) {
        if (!o.create) throw ConfigError(base.mark(), base.path_of(walked), "no such section to set '" + o.path + "' in");
        parent[parts[k]] = YAML::Node(YAML::NodeType::Map);
        next = parent[parts[k]];
      }
      if (!next.IsMap()) throw ConfigError(base.mark(), base.path_of(walked), "not a map: cannot set '" + o.path + "'");
      parent.reset(next);
    }
    if (!parent.IsMap()) throw ConfigError(base.mark(), base.path(), "not a map: cannot set '" + o.path + "'");
    if (!o.create && !parent[parts.back()]) {
      throw ConfigError(base.mark(), base.path_of(o.path), "no parameter '" + o.path + "' to set");
    }
    parent[parts.back()] = value;
  }
  ConfigDocument doc;
  doc.path_ = name;
  doc.directory_ = directory;
  std::string text;
  canonical(tree, text);
  doc.hash_ = fnv1a_hex(text);
  doc.root_ = make_root_view(tree, base.file());
  return doc;
}

std::filesystem::path ConfigDocument::directory() const {
  if (!directory_.empty()) return directory_;
  auto dir = path_.parent_path();
  return dir.empty() ? std::filesystem::path(".") : dir;
}

}  // namespace plumage
