#include "plumage/checksum.hpp"
#include "plumage/config_document.hpp"

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <algorithm>
#include <charconv>
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
    // Sort an index, not the nodes: assigning a YAML::Node writes through to the document.
    std::vector<std::pair<std::string, std::size_t>> keys;
    std::vector<YAML::Node> values;
    for (auto it = n.begin(); it != n.end(); ++it) {
      keys.emplace_back(it->first.Scalar(), values.size());
      values.push_back(it->second);
    }
    std::sort(keys.begin(), keys.end());
    out += "{";
    for (const auto& [key, k] : keys) {
      out += std::to_string(key.size()) + ":" + key + "=";
      canonical(values[k], out);
      out += ",";
    }
    out += "}";
  }
}

std::vector<std::string> split_path(const std::string& path) {
  std::vector<std::string> parts;
  for (std::size_t start = 0;;) {
    const std::size_t dot = path.find('.', start);
    parts.push_back(path.substr(start, dot == std::string::npos ? std::string::npos : dot - start));
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  return parts;
}

// `base` with the value at parts[k..] replaced: new map nodes along the path, every other key and
// value node reused (force_insert keeps them, with their file positions).
YAML::Node replaced(const YAML::Node& base, const std::vector<std::string>& parts, std::size_t k,
                    const YAML::Node& value, const ConfigDocument::Override& o, const ParamView& where) {
  const std::string walked = [&] {
    std::string w;
    for (std::size_t i = 0; i <= k; ++i) w += (i ? "." : "") + parts[i];
    return w;
  }();
  // A list item by its index ("layers.0.thickness_nm"): a new sequence, the other items reused.
  if (base && base.IsSequence()) {
    std::size_t index = 0;
    const auto [end, ec] = std::from_chars(parts[k].data(), parts[k].data() + parts[k].size(), index);
    if (ec != std::errc{} || end != parts[k].data() + parts[k].size() || index >= base.size()) {
      throw ConfigError(where.mark(), where.path_of(walked),
                        "no list item '" + parts[k] + "' (the list has " + std::to_string(base.size()) +
                            " items, numbered from 0): cannot set '" + o.path + "' (" + o.source + ")");
    }
    YAML::Node out(YAML::NodeType::Sequence);
    for (std::size_t i = 0; i < base.size(); ++i)
      out.push_back(i != index ? base[i] : k + 1 == parts.size() ? value : replaced(base[i], parts, k + 1, value, o, where));
    return out;
  }
  if (base && !base.IsNull() && !base.IsMap()) {
    throw ConfigError(where.mark(), where.path_of(walked), "not a map: cannot set '" + o.path + "' (" + o.source + ")");
  }
  YAML::Node out(YAML::NodeType::Map);
  bool found = false;
  if (base && base.IsMap()) {
    for (auto it = base.begin(); it != base.end(); ++it) {
      if (it->first.Scalar() != parts[k]) {
        out.force_insert(it->first, it->second);
        continue;
      }
      found = true;
      out.force_insert(it->first, k + 1 == parts.size() ? value : replaced(it->second, parts, k + 1, value, o, where));
    }
  }
  if (!found) {
    if (!o.create) {
      throw ConfigError(where.mark(), where.path_of(walked),
                        "no parameter '" + walked + "' to set to " + o.yaml + " (" + o.source + ")");
    }
    out.force_insert(YAML::Node(parts[k]), k + 1 == parts.size() ? value : replaced(YAML::Node(), parts, k + 1, value, o, where));
  }
  return out;
}

}  // namespace

std::string canonical_text(const ParamView& view) {
  std::string out;
  canonical(view.state()->node, out);
  return out;
}

ConfigDocument ConfigDocument::derive(const ParamView& base, const std::vector<Override>& overrides,
                                      const std::filesystem::path& directory, const std::string& name) {
  YAML::Node tree = base.state()->node;
  auto sources = std::make_shared<std::vector<std::pair<YAML::Node, std::string>>>();
  for (const Override& o : overrides) {
    YAML::Node value;
    try {
      value = YAML::Load(o.yaml);
    } catch (const YAML::ParserException& e) {
      throw ConfigError({o.source, 0, 0}, base.path_of(o.path), "not a YAML value: '" + o.yaml + "' (" + e.msg + ")");
    }
    tree.reset(replaced(tree, split_path(o.path), 0, value, o, base));  // reset: `=` would write into base
    sources->emplace_back(value, o.source);
  }
  ConfigDocument doc;
  doc.path_ = name;
  doc.directory_ = directory;
  std::string text;
  canonical(tree, text);
  doc.hash_ = fnv1a_hex(text);
  doc.root_ = make_root_view(tree, base.file());
  doc.root_.state()->overrides = std::move(sources);
  return doc;
}

std::filesystem::path ConfigDocument::directory() const {
  if (!directory_.empty()) return directory_;
  auto dir = path_.parent_path();
  return dir.empty() ? std::filesystem::path(".") : dir;
}

}  // namespace plumage
