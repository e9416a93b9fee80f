// ParamView over yaml-cpp nodes, with known-key bookkeeping and located errors.
#include "plumage/params.hpp"

#include "plumage/param_table.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

#include "yaml_state.hpp"

namespace plumage {

namespace {

SourceMark mark_from(const YAML::Mark& m, const std::string& file) {
  if (m.is_null() || m.line < 0) return {file, 0, 0};
  return {file, m.line + 1, m.column + 1};
}

// The position of `node` in messages: its override's source when a derived document replaced it.
SourceMark mark_of_node(const ParamView::State& s, const YAML::Node& node) {
  if (s.overrides) {
    for (const auto& [value, source] : *s.overrides)
      if (value.is(node)) return {source, 0, 0};
  }
  return mark_from(node.Mark(), s.file);
}

std::string join_path(const std::string& base, std::string_view key) {
  if (base.empty()) return std::string(key);
  return base + "." + std::string(key);
}

std::string quote_list(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) {
    if (!out.empty()) out += ", ";
    out += n;
  }
  return out;
}

}  // namespace

bool Limits::admits(double v) const {
  if (!std::isfinite(v)) return false;
  if (min && (min_exclusive ? !(v > *min) : !(v >= *min))) return false;
  if (max && (max_exclusive ? !(v < *max) : !(v <= *max))) return false;
  return true;
}

// Shortest round-trip form (format_param_number), so an integer bound reads as one: 1048576, not
// 1.04858e+06.
std::string Limits::describe() const {
  if (min && max) {
    return std::string(min_exclusive ? "in (" : "in [") + format_param_number(*min) + ", " +
           format_param_number(*max) + (max_exclusive ? ")" : "]");
  }
  if (min) return (min_exclusive ? "> " : ">= ") + format_param_number(*min);
  if (max) return (max_exclusive ? "< " : "<= ") + format_param_number(*max);
  return "finite";
}

ParamView::ParamView() : state_(std::make_shared<State>()) {
  state_->node = YAML::Node(YAML::NodeType::Map);
  state_->file = "<command line>";
}

ParamView::ParamView(std::shared_ptr<State> state) : state_(std::move(state)) {}

SourceMark ParamView::mark() const { return mark_of_node(*state_, state_->node); }

SourceMark ParamView::mark_of(std::string_view key) const {
  if (state_->node.IsMap()) {
    for (auto it = state_->node.begin(); it != state_->node.end(); ++it) {
      if (it->first.Scalar() == key) {
        auto m = mark_of_node(*state_, it->second);
        if (m.file != state_->file) return m;  // an override
        if (m.line == 0) m = mark_from(it->first.Mark(), state_->file);
        return m;
      }
    }
  }
  return mark();
}

const std::string& ParamView::path() const { return state_->path; }
std::string ParamView::path_of(std::string_view key) const { return join_path(state_->path, key); }
const std::string& ParamView::file() const { return state_->file; }

bool ParamView::is_map() const { return state_->node.IsMap(); }
bool ParamView::is_sequence() const { return state_->node.IsSequence(); }
bool ParamView::is_scalar() const { return state_->node.IsScalar(); }
bool ParamView::is_null() const { return !state_->node || state_->node.IsNull(); }

void ParamView::accept(std::string_view key) const { state_->known.insert(std::string(key)); }

void ParamView::note(const ParamSpec& spec, bool defaulted) const {
  for (auto& [row, absent] : state_->notes) {
    if (row.name == spec.name) {
      row = spec;
      absent = defaulted;
      return;
    }
  }
  state_->notes.emplace_back(spec, defaulted);
}

std::vector<std::string> ParamView::known_keys() const { return {state_->known.begin(), state_->known.end()}; }

bool ParamView::has(std::string_view key) const {
  accept(key);
  if (!state_->node.IsMap()) return false;
  const YAML::Node& n = state_->node;
  return static_cast<bool>(n[std::string(key)]);
}

void ParamView::fail(std::string_view key, const std::string& message) const {
  throw ConfigError(mark_of(key), path_of(key), message);
}

void ParamView::fail_here(const std::string& message) const {
  throw ConfigError(mark(), state_->path, message);
}

namespace {

YAML::Node lookup(const ParamView& view, std::string_view key) {
  const YAML::Node& n = view.state()->node;
  if (!n.IsMap()) view.fail_here("expected a map of parameters");
  return n[std::string(key)];
}

YAML::Node require(const ParamView& view, std::string_view key) {
  view.accept(key);
  YAML::Node v = lookup(view, key);
  if (!v) view.fail(key, "missing required key '" + std::string(key) + "'");
  return v;
}

double to_number(const ParamView& view, std::string_view key, const YAML::Node& v,
                 const Limits& limits) {
  if (!v.IsScalar()) view.fail(key, "expected a number");
  double x = 0;
  try {
    x = v.as<double>();
  } catch (const YAML::Exception&) {
    view.fail(key, "expected a number, got '" + v.Scalar() + "'");
  }
  if (!limits.admits(x)) {
    view.fail(key, "value " + v.Scalar() + " is out of range: must be " + limits.describe());
  }
  return x;
}

}  // namespace

double ParamView::number(std::string_view key, Limits limits) const {
  return to_number(*this, key, require(*this, key), limits);
}

double ParamView::number_or(std::string_view key, double fallback, Limits limits) const {
  accept(key);
  YAML::Node v = lookup(*this, key);
  if (!v || v.IsNull()) return fallback;
  return to_number(*this, key, v, limits);
}

std::int64_t ParamView::integer(std::string_view key, Limits limits) const {
  YAML::Node v = require(*this, key);
  if (!v.IsScalar()) fail(key, "expected an integer");
  long long x = 0;
  try {
    x = v.as<long long>();
  } catch (const YAML::Exception&) {
    fail(key, "expected an integer, got '" + v.Scalar() + "'");
  }
  if (!limits.admits(static_cast<double>(x))) {
    fail(key, "value " + v.Scalar() + " is out of range: must be " + limits.describe());
  }
  return x;
}

std::int64_t ParamView::integer_or(std::string_view key, std::int64_t fallback,
                                   Limits limits) const {
  accept(key);
  YAML::Node v = lookup(*this, key);
  if (!v || v.IsNull()) return fallback;
  return integer(key, limits);
}

bool ParamView::boolean_or(std::string_view key, bool fallback) const {
  accept(key);
  YAML::Node v = lookup(*this, key);
  if (!v || v.IsNull()) return fallback;
  if (!v.IsScalar()) fail(key, "expected true or false");
  try {
    return v.as<bool>();
  } catch (const YAML::Exception&) {
    fail(key, "expected true or false, got '" + v.Scalar() + "'");
  }
}

std::string ParamView::text(std::string_view key) const {
  YAML::Node v = require(*this, key);
  if (!v.IsScalar()) fail(key, "expected a text value");
  return v.Scalar();
}

std::string ParamView::text_or(std::string_view key, std::string fallback) const {
  accept(key);
  YAML::Node v = lookup(*this, key);
  if (!v || v.IsNull()) return fallback;
  return text(key);
}

std::string ParamView::choice(std::string_view key,
                              std::span<const std::string_view> allowed) const {
  std::string word = text(key);
  std::vector<std::string> names(allowed.begin(), allowed.end());
  if (std::find(names.begin(), names.end(), word) != names.end()) return word;
  std::string msg = "unknown value '" + word + "'";
  if (auto near = nearest_name(word, names)) msg += " (did you mean '" + *near + "'?)";
  msg += "; allowed: " + quote_list(names);
  fail(key, msg);
}

std::string ParamView::choice_or(std::string_view key, std::span<const std::string_view> allowed,
                                 std::string fallback) const {
  accept(key);
  YAML::Node v = lookup(*this, key);
  if (!v || v.IsNull()) return fallback;
  return choice(key, allowed);
}

std::pair<double, double> ParamView::interval(std::string_view key, Limits limits) const {
  YAML::Node v = require(*this, key);
  if (!v.IsSequence() || v.size() != 2) fail(key, "expected an interval [low, high]");
  double lo = to_number(*this, key, v[0], limits);
  double hi = to_number(*this, key, v[1], limits);
  if (lo > hi) {
    fail(key, "interval is inverted: low " + v[0].Scalar() + " > high " + v[1].Scalar());
  }
  return {lo, hi};
}

std::vector<double> ParamView::numbers(std::string_view key, Limits limits) const {
  YAML::Node v = require(*this, key);
  if (!v.IsSequence()) fail(key, "expected a list of numbers");
  std::vector<double> out;
  out.reserve(v.size());
  for (const auto& item : v) out.push_back(to_number(*this, key, item, limits));
  return out;
}

std::shared_ptr<ParamView::State> ParamView::State::make_child(const YAML::Node& node,
                                                               std::string child_path) {
  auto child = std::make_shared<State>();
  child->node = node;
  child->file = file;
  child->path = std::move(child_path);
  child->overrides = overrides;
  children.push_back(child);
  return child;
}

ParamView ParamView::node(std::string_view key) const {
  YAML::Node v = require(*this, key);
  std::string k(key);
  auto found = state_->child_by_key.find(k);
  if (found != state_->child_by_key.end()) return ParamView(found->second);
  auto child = state_->make_child(v, path_of(key));
  state_->child_by_key.emplace(k, child);
  return ParamView(child);
}

ParamView ParamView::child(std::string_view key) const {
  ParamView v = node(key);
  if (!v.is_map()) fail(key, "expected a map of parameters");
  return v;
}

std::optional<ParamView> ParamView::child_if(std::string_view key) const {
  if (!has(key)) return std::nullopt;
  return child(key);
}

std::vector<ParamView> ParamView::items() const {
  if (!is_sequence()) fail_here("expected a list");
  if (!state_->items_made) {
    std::size_t i = 0;
    for (const auto& item : state_->node) {
      state_->item_states.push_back(
          state_->make_child(item, state_->path + "[" + std::to_string(i++) + "]"));
    }
    state_->items_made = true;
  }
  std::vector<ParamView> out;
  for (const auto& s : state_->item_states) out.emplace_back(s);
  return out;
}

std::vector<ParamView> ParamView::items(std::string_view key) const {
  ParamView list = node(key);
  if (!list.is_sequence()) fail(key, "expected a list");
  return list.items();
}

std::vector<std::string> ParamView::keys() const {
  std::vector<std::string> out;
  if (!is_map()) return out;
  for (auto it = state_->node.begin(); it != state_->node.end(); ++it) {
    out.push_back(it->first.Scalar());
  }
  return out;
}

std::string ParamView::scalar_text() const {
  if (!is_scalar()) fail_here("expected a single value");
  return state_->node.Scalar();
}

double ParamView::scalar_number(Limits limits) const {
  if (!is_scalar()) fail_here("expected a number");
  double x = 0;
  try {
    x = state_->node.as<double>();
  } catch (const YAML::Exception&) {
    fail_here("expected a number, got '" + state_->node.Scalar() + "'");
  }
  if (!limits.admits(x)) {
    fail_here("value " + state_->node.Scalar() + " is out of range: must be " + limits.describe());
  }
  return x;
}

void ParamView::finish() const {
  if (is_map()) {
    std::vector<std::string> known(state_->known.begin(), state_->known.end());
    for (auto it = state_->node.begin(); it != state_->node.end(); ++it) {
      const std::string& key = it->first.Scalar();
      if (state_->known.count(key)) continue;
      std::string msg = "unknown key '" + key + "'";
      if (auto near = nearest_name(key, known)) msg += " (did you mean '" + *near + "'?)";
      if (!known.empty()) msg += "; valid keys here: " + quote_list(known);
      throw ConfigError(mark_from(it->first.Mark(), state_->file), join_path(state_->path, key),
                        msg);
    }
  }
  for (const auto& child : state_->children) ParamView(child).finish();
}

std::optional<std::string> nearest_name(std::string_view word,
                                        std::span<const std::string> candidates) {
  auto lower = [](std::string_view s) {
    std::string out(s);
    for (auto& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
  };
  const std::string a = lower(word);
  std::optional<std::string> best;
  std::size_t best_distance = std::max<std::size_t>(2, a.size() / 3) + 1;
  for (const auto& candidate : candidates) {
    const std::string b = lower(candidate);
    // Levenshtein distance, two rows.
    std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
      cur[0] = i;
      for (std::size_t j = 1; j <= b.size(); ++j) {
        cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] != b[j - 1])});
      }
      std::swap(prev, cur);
    }
    if (prev[b.size()] < best_distance) {
      best_distance = prev[b.size()];
      best = candidate;
    }
  }
  return best;
}

}  // namespace plumage
