#include "plumage/checksum.hpp"
#include "plumage/config_document.hpp"

#include <yaml-cpp/yaml.h>

#include <cstdint>
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

std::filesystem::path ConfigDocument::directory() const {
  auto dir = path_.parent_path();
  return dir.empty() ? std::filesystem::path(".") : dir;
}

}  // namespace plumage
