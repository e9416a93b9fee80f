// Typed, validating view of a configuration node (a YAML map, list or scalar).
//
// Plug-in factories read their parameters only through ParamView. Every read records the key as
// known, so that after construction the host can reject keys nobody asked for (typos) with the
// nearest valid name. Every failed read throws ConfigError naming file:line:column and the dotted
// path of the field. yaml-cpp stays an implementation detail of core (pimpl), so out-of-tree
// plug-ins need no YAML headers.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "plumage/error.hpp"

namespace plumage {

struct ParamSpec;  // plugin.hpp

// Admissible interval of a number. Unset ends are unbounded.
struct Limits {
  std::optional<double> min;
  std::optional<double> max;
  bool min_exclusive = false;
  bool max_exclusive = false;

  static Limits positive() { return {0.0, std::nullopt, true, false}; }
  static Limits non_negative() { return {0.0, std::nullopt, false, false}; }
  static Limits closed(double lo, double hi) { return {lo, hi, false, false}; }
  static Limits at_least(double lo) { return {lo, std::nullopt, false, false}; }
  static Limits unit_interval() { return closed(0.0, 1.0); }
  // Every wavelength a command or config takes (issue 23): 100 nm (vacuum UV, well below the
  // ~300 nm of birds' UV vision) to 5 µm (mid-infrared, past the near-IR). The materials'
  // dispersion (paper Eq. 1, Cauchy fits in the visible) means nothing far outside; 5 nm or
  // 1e9 nm is a typo, not a study.
  static Limits wavelength_nm() { return closed(100.0, 5000.0); }
  // Scene coordinates (positions, centres, corners, edges) in mm: within a kilometre of the origin.
  // A scene is a bird or a feather in a room; the renderer's single-precision geometry (Embree)
  // keeps no detail of a 0.01 mm barbule that far out, and aborts on bounds near float's limit.
  static Limits scene_coordinate_mm() { return closed(-1e6, 1e6); }
  // Scene sizes (lengths, radii, widths) in mm: positive, at most a kilometre (as above).
  static Limits scene_length_mm() { return {0.0, 1e6, true, false}; }

  bool admits(double v) const;
  std::string describe() const;  // e.g. "> 0", "in [0, 1]"
};

class ParamView {
 public:
  struct State;  // shared bookkeeping (node, known keys, children); defined in params.cpp

  ParamView();  // an empty map with no source (parameters given on the command line)
  explicit ParamView(std::shared_ptr<State> state);

  // Where this node is, and its dotted path from the document root ("structure.roughness").
  SourceMark mark() const;
  SourceMark mark_of(std::string_view key) const;  // the key's value, or this node if absent
  const std::string& path() const;
  std::string path_of(std::string_view key) const;
  const std::string& file() const;

  bool is_map() const;
  bool is_sequence() const;
  bool is_scalar() const;
  bool is_null() const;

  // Map access. Each call marks `key` as known. Required reads throw when the key is missing.
  bool has(std::string_view key) const;
  double number(std::string_view key, Limits limits = {}) const;
  double number_or(std::string_view key, double fallback, Limits limits = {}) const;
  std::int64_t integer(std::string_view key, Limits limits = {}) const;
  std::int64_t integer_or(std::string_view key, std::int64_t fallback, Limits limits = {}) const;
  bool boolean_or(std::string_view key, bool fallback) const;
  std::string text(std::string_view key) const;
  std::string text_or(std::string_view key, std::string fallback) const;
  // One of `allowed`; an unknown word is an error naming the nearest allowed one.
  std::string choice(std::string_view key, std::span<const std::string_view> allowed) const;
  std::string choice_or(std::string_view key, std::span<const std::string_view> allowed,
                        std::string fallback) const;
  // [lo, hi] with lo ≤ hi (an inverted range is an error), both within `limits`.
  std::pair<double, double> interval(std::string_view key, Limits limits = {}) const;
  std::vector<double> numbers(std::string_view key, Limits limits = {}) const;

  // Sub-nodes. child() requires a map; node() accepts any kind; items() lists a sequence.
  ParamView child(std::string_view key) const;
  std::optional<ParamView> child_if(std::string_view key) const;
  ParamView node(std::string_view key) const;
  std::vector<ParamView> items(std::string_view key) const;  // key must hold a sequence
  std::vector<ParamView> items() const;                      // this node is a sequence
  std::vector<std::string> keys() const;                     // map keys in file order

  // Scalar access on this node itself (for list items and polymorphic values).
  std::string scalar_text() const;
  double scalar_number(Limits limits = {}) const;

  // Mark a key as known without reading it (e.g. a key consumed by the host).
  void accept(std::string_view key) const;
  // The keys of this map read (or accepted) so far, sorted; present in the file or not.
  std::vector<std::string> known_keys() const;

  // Reject unknown keys in this map and in every child view handed out so far, recursively.
  void finish() const;

  // What a declaration (ParamTable) read here: its row and whether the key was absent, so that
  // `plumage check --resolved` can print every parameter with its default, unit and doc.
  void note(const ParamSpec& spec, bool defaulted) const;

  [[noreturn]] void fail(std::string_view key, const std::string& message) const;
  [[noreturn]] void fail_here(const std::string& message) const;

  const std::shared_ptr<State>& state() const { return state_; }

 private:
  std::shared_ptr<State> state_;
};

// Nearest candidate by edit distance, if it is close enough to be a plausible typo.
std::optional<std::string> nearest_name(std::string_view word,
                                        std::span<const std::string> candidates);

}  // namespace plumage
