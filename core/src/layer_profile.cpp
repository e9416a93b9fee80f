#include "plumage/layer_profile.hpp"

#include <cctype>
#include <charconv>
#include <stdexcept>

namespace plumage {

namespace {

std::string trim(std::string_view s) {
  std::size_t a = 0, b = s.size();
  while (a < b && std::isspace(static_cast<unsigned char>(s[a]))) ++a;
  while (b > a && std::isspace(static_cast<unsigned char>(s[b - 1]))) --b;
  return std::string(s.substr(a, b - a));
}

// Splits on '|' outside braces and parentheses.
std::vector<std::string> split_top_level(std::string_view text) {
  std::vector<std::string> parts;
  int depth = 0;
  std::size_t start = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    char c = text[i];
    if (c == '{' || c == '(') ++depth;
    if (c == '}' || c == ')') {
      if (--depth < 0) throw std::invalid_argument("unbalanced '" + std::string(1, c) + "'");
    }
    if (c == '|' && depth == 0) {
      parts.push_back(trim(text.substr(start, i - start)));
      start = i + 1;
    }
  }
  if (depth != 0) throw std::invalid_argument("unbalanced braces in stack");
  parts.push_back(trim(text.substr(start)));
  return parts;
}

void append_layers(const std::string& piece, std::vector<Layer>& out) {
  if (piece.empty()) throw std::invalid_argument("empty layer between '|'");
  if (piece.front() == '{') {
    auto close = piece.rfind('}');
    auto star = piece.find('*', close);
    if (close == std::string::npos || star == std::string::npos) {
      throw std::invalid_argument("'" + piece + "': a group is written {layer | layer}*count");
    }
    std::string count_text = trim(piece.substr(star + 1));
    int count = 0;
    auto [ptr, ec] = std::from_chars(count_text.data(), count_text.data() + count_text.size(), count);
    if (ec != std::errc() || ptr != count_text.data() + count_text.size() || count < 1) {
      throw std::invalid_argument("'" + piece + "': repeat count must be a positive integer");
    }
    std::vector<Layer> group;
    for (const auto& inner : split_top_level(piece.substr(1, close - 1))) append_layers(inner, group);
    for (int i = 0; i < count; ++i) out.insert(out.end(), group.begin(), group.end());
    return;
  }
  auto space = piece.find_last_of(" \t");
  if (space == std::string::npos) {
    throw std::invalid_argument("'" + piece + "': a layer is written '<material> <thickness_nm>'");
  }
  std::string thickness_text = trim(piece.substr(space + 1));
  double thickness = 0;
  auto [ptr, ec] = std::from_chars(thickness_text.data(),
                                   thickness_text.data() + thickness_text.size(), thickness);
  if (ec != std::errc() || ptr != thickness_text.data() + thickness_text.size()) {
    throw std::invalid_argument("'" + piece + "': thickness '" + thickness_text +
                                "' is not a number (nm)");
  }
  if (!(thickness >= 0.0)) throw std::invalid_argument("'" + piece + "': negative thickness");
  out.push_back({parse_material_text(piece.substr(0, space)), thickness});
}

void parse_layer_items(const ParamView& list_owner, std::vector<Layer>& out) {
  auto items = list_owner.items("layers");
  for (const auto& item : items) {
    if (!item.is_map()) item.fail_here("expected {material: .., thickness_nm: ..} or {repeat: .., layers: [..]}");
    if (item.has("repeat")) {
      auto count = item.integer("repeat", Limits::at_least(1));
      std::vector<Layer> group;
      parse_layer_items(item, group);
      if (group.empty()) item.fail("layers", "a repeated group needs at least one layer");
      for (std::int64_t i = 0; i < count; ++i) out.insert(out.end(), group.begin(), group.end());
    } else {
      Material m = parse_material(item, "material");
      double t = item.number("thickness_nm", Limits::non_negative());
      out.push_back({m, t});
    }
    item.finish();
  }
}

}  // namespace

double LayerProfile::total_thickness_nm() const {
  double t = 0;
  for (const auto& l : layers) t += l.thickness_nm;
  return t;
}

LayerProfile parse_layer_profile(const ParamView& node) {
  LayerProfile profile;
  profile.ambient = node.has("ambient") ? parse_material(node, "ambient") : Material::air();
  profile.substrate = node.has("substrate") ? parse_material(node, "substrate") : Material::air();
  parse_layer_items(node, profile.layers);
  if (profile.layers.empty()) node.fail("layers", "the stack has no layers");
  return profile;
}

LayerProfile parse_stack_text(std::string_view text) {
  auto parts = split_top_level(text);
  if (parts.size() < 2) {
    throw std::invalid_argument("a stack needs at least an ambient and a substrate: 'air | keratin'");
  }
  LayerProfile profile;
  profile.ambient = parse_material_text(parts.front());
  profile.substrate = parse_material_text(parts.back());
  for (std::size_t i = 1; i + 1 < parts.size(); ++i) append_layers(parts[i], profile.layers);
  return profile;
}

std::string describe(const LayerProfile& profile) {
  std::string out = profile.ambient.name();
  for (const auto& l : profile.layers) {
    char buf[32];
    auto [ptr, ec] = std::to_chars(buf, buf + sizeof buf, l.thickness_nm);
    out += " | " + l.material.name() + " " + std::string(buf, ptr);
  }
  return out + " | " + profile.substrate.name();
}

}  // namespace plumage
