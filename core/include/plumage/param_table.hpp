// One declaration per parameter (issue 22): name, type, unit, default, range and a one-line doc,
// bound to a field of an options struct. The same declaration reads the value from a config
// section (ParamView: located errors, range checks), supplies the default, and documents the
// parameter (`plumage plugins describe`, docs/parameters.md). A plug-in builds one table per
// type it registers and passes `table.specs()` as PluginInfo::params; the host then refuses any
// key the factory read that the table does not declare (plugin_registry.cpp).
//
//   struct Options { double ppw = 0; Method method{}; };
//   const ParamTable<Options>& options_table() {
//     static const auto t = ParamTable<Options>{}
//         .number("points_per_wavelength", &Options::ppw, "1", 30.0, Limits::positive(),
//                 "segments per wavelength")
//         .choice("method", &Options::method, {{"dense", Method::dense}, {"gmres", Method::gmres}},
//                 Method::dense, "linear solver");
//     return t;
//   }
//   Options o = options_table().read(params);
//
// A field is a pointer to a data member or any callable T& -> V& (for nested structs).
// `only_if(predicate, "when")` makes the last entry conditional on what was read before it (a
// model switch); a conditional entry that does not apply is not read, so giving it is an unknown
// key. `custom` entries keep the declaration for values a generic reader cannot take (materials,
// lists of maps): the reader function reads that one key.
#pragma once

#include <cstdint>
#include <functional>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "plumage/params.hpp"
#include "plumage/plugin.hpp"

namespace plumage {

// Tag for a parameter without a default.
struct RequiredParam {};
inline constexpr RequiredParam required{};

// Shortest text that reads back to the same double ("30", "1e-08", "0.25").
std::string format_param_number(double value);
std::string format_param_interval(std::pair<double, double> value);
std::string format_param_numbers(const std::vector<double>& values);

// A field adaptor that stores the value read times `factor`, for a parameter given in one unit and
// kept in another (a length in µm kept in nm): into one number, or into the two ends of an interval.
//   .number("width_um", scaled(&Spec::width_nm, 1000.0), "um", required, Limits::positive(), "...")
struct Scaled {
  double* first;
  double* second;  // the interval's upper end; null for a number
  double factor;
  Scaled& operator=(double value) {
    *first = factor * value;
    return *this;
  }
  Scaled& operator=(const std::pair<double, double>& value) {
    *first = factor * value.first;
    *second = factor * value.second;
    return *this;
  }
};
template <class T>
auto scaled(double T::*member, double factor) {
  return [member, factor](T& o) { return Scaled{&(o.*member), nullptr, factor}; };
}
template <class T>
auto scaled(std::pair<double, double> T::*member, double factor) {
  return [member, factor](T& o) { return Scaled{&(o.*member).first, &(o.*member).second, factor}; };
}

template <class T>
class ParamTable {
 public:
  using Reader = std::function<void(const ParamView& section, T& out)>;
  using Predicate = std::function<bool(const T&)>;

  // A floating-point parameter.
  template <class Field>
  ParamTable& number(std::string name, Field field, std::string unit, double fallback, Limits limits,
                     std::string doc) {
    return add_number<double>(std::move(name), std::move(field), std::move(unit), fallback, limits,
                              std::move(doc));
  }
  template <class Field>
  ParamTable& number(std::string name, Field field, std::string unit, RequiredParam, Limits limits,
                     std::string doc) {
    return add_number<double>(std::move(name), std::move(field), std::move(unit), std::nullopt, limits,
                              std::move(doc));
  }
  // An optional number: absent leaves the field empty (the meaning of "unset" is in default_text).
  template <class Field>
  ParamTable& optional_number(std::string name, Field field, std::string unit, std::string default_text,
                              Limits limits, std::string doc) {
    Entry e = entry(name, "number", std::move(unit), std::move(default_text), limits, std::move(doc));
    e.set_default = [field](T& o) { std::invoke(field, o).reset(); };
    e.read = [field, name, limits](const ParamView& p, T& o) {
      if (p.has(name) && !p.node(name).is_null()) std::invoke(field, o) = p.number(name, limits);
    };
    return push(std::move(e));
  }
  // An integer parameter (field of any integer type).
  template <class Field>
  ParamTable& integer(std::string name, Field field, std::string unit, std::int64_t fallback, Limits limits,
                      std::string doc) {
    return add_integer(std::move(name), std::move(field), std::move(unit), fallback, limits, std::move(doc));
  }
  template <class Field>
  ParamTable& integer(std::string name, Field field, std::string unit, RequiredParam, Limits limits,
                      std::string doc) {
    return add_integer(std::move(name), std::move(field), std::move(unit), std::nullopt, limits, std::move(doc));
  }
  template <class Field>
  ParamTable& boolean(std::string name, Field field, bool fallback, std::string doc) {
    Entry e = entry(name, "bool", "-", fallback ? "true" : "false", {}, std::move(doc));
    e.set_default = [field, fallback](T& o) { std::invoke(field, o) = fallback; };
    e.read = [field, name, fallback](const ParamView& p, T& o) { std::invoke(field, o) = p.boolean_or(name, fallback); };
    return push(std::move(e));
  }
  // An optional switch: absent leaves the field empty (default_text says what that means).
  template <class Field>
  ParamTable& optional_boolean(std::string name, Field field, std::string default_text, std::string doc) {
    Entry e = entry(name, "bool", "-", std::move(default_text), {}, std::move(doc));
    e.set_default = [field](T& o) { std::invoke(field, o).reset(); };
    e.read = [field, name](const ParamView& p, T& o) {
      if (p.has(name) && !p.node(name).is_null()) std::invoke(field, o) = p.boolean_or(name, false);
    };
    return push(std::move(e));
  }
  template <class Field>
  ParamTable& text(std::string name, Field field, std::string fallback, std::string doc) {
    Entry e = entry(name, "text", "-", fallback.empty() ? "\"\"" : fallback, {}, std::move(doc));
    e.set_default = [field, fallback](T& o) { std::invoke(field, o) = fallback; };
    e.read = [field, name, fallback](const ParamView& p, T& o) { std::invoke(field, o) = p.text_or(name, fallback); };
    return push(std::move(e));
  }
  template <class Field>
  ParamTable& text(std::string name, Field field, RequiredParam, std::string doc) {
    Entry e = entry(name, "text", "-", "required", {}, std::move(doc));
    e.read = [field, name](const ParamView& p, T& o) { std::invoke(field, o) = p.text(name); };
    return push(std::move(e));
  }
  // One word of `options`, stored as its value (an enum, or the word itself).
  template <class Field, class V>
  ParamTable& choice(std::string name, Field field, std::vector<std::pair<std::string_view, V>> options,
                     V fallback, std::string doc) {
    return add_choice(std::move(name), std::move(field), std::move(options), std::optional<V>(fallback),
                      std::move(doc));
  }
  template <class Field, class V>
  ParamTable& choice(std::string name, Field field, std::vector<std::pair<std::string_view, V>> options,
                     RequiredParam, std::string doc) {
    return add_choice(std::move(name), std::move(field), std::move(options), std::optional<V>(), std::move(doc));
  }
  // [low, high] with low <= high, both within limits.
  template <class Field>
  ParamTable& interval(std::string name, Field field, std::string unit, std::pair<double, double> fallback,
                       Limits limits, std::string doc) {
    Entry e = entry(name, "interval", std::move(unit), format_param_interval(fallback), limits, std::move(doc));
    e.set_default = [field, fallback](T& o) { std::invoke(field, o) = fallback; };
    e.read = [field, name, limits](const ParamView& p, T& o) {
      if (p.has(name)) std::invoke(field, o) = p.interval(name, limits);
    };
    return push(std::move(e));
  }
  template <class Field>
  ParamTable& interval(std::string name, Field field, std::string unit, RequiredParam, Limits limits,
                       std::string doc) {
    Entry e = entry(name, "interval", std::move(unit), "required", limits, std::move(doc));
    e.read = [field, name, limits](const ParamView& p, T& o) { std::invoke(field, o) = p.interval(name, limits); };
    return push(std::move(e));
  }
  // A list of numbers, each within limits.
  template <class Field>
  ParamTable& numbers(std::string name, Field field, std::string unit, std::vector<double> fallback,
                      Limits limits, std::string doc) {
    Entry e = entry(name, "list", std::move(unit), format_param_numbers(fallback), limits, std::move(doc));
    e.set_default = [field, fallback](T& o) { std::invoke(field, o) = fallback; };
    e.read = [field, name, limits](const ParamView& p, T& o) {
      if (p.has(name)) std::invoke(field, o) = p.numbers(name, limits);
    };
    return push(std::move(e));
  }
  // A nested map read with its own table (docs list its rows as name.sub). Absent: the nested
  // table's defaults, or an error when `required` is given.
  template <class Field, class U>
  ParamTable& section(std::string name, Field field, const ParamTable<U>& table, std::string doc,
                      bool is_required = false) {
    Entry e = entry(name, "map", "-", is_required ? "required" : "{}", {}, std::move(doc));
    e.set_default = [field, &table](T& o) { std::invoke(field, o) = table.defaults(); };
    e.read = [field, name, &table, is_required](const ParamView& p, T& o) {
      if (is_required || p.has(name)) std::invoke(field, o) = table.read(p.child(name));
    };
    e.nested = table.specs();
    return push(std::move(e));
  }
  // A value the generic readers cannot take; `read` reads `name` from the section (and may leave
  // the field at its default when absent). `set_default` may be empty.
  ParamTable& custom(std::string name, std::string type, std::string unit, std::string default_text,
                     std::string doc, Reader read, std::function<void(T&)> set_default = {}) {
    Entry e = entry(std::move(name), std::move(type), std::move(unit), std::move(default_text), {}, std::move(doc));
    e.read = std::move(read);
    e.set_default = std::move(set_default);
    return push(std::move(e));
  }
  // Documentation rows of a nested structure read by the previous custom entry (e.g. a list of
  // maps), listed as name.sub.
  ParamTable& nested_specs(std::vector<ParamSpec> rows) {
    entries_.back().nested = std::move(rows);
    return *this;
  }
  // The previous entry applies only when `predicate` holds for what was read before it.
  ParamTable& only_if(Predicate predicate, std::string when) {
    Entry& e = entries_.back();
    e.applies = std::move(predicate);
    e.spec.condition = std::move(when);
    return *this;
  }
  // Overrides the default's text in the docs (e.g. "cortex_nm" for a default taken from another field).
  ParamTable& default_text(std::string text) {
    entries_.back().spec.default_value = std::move(text);
    return *this;
  }
  // Rows of another table appended (a shared block such as the barbule outline).
  template <class Field, class U>
  ParamTable& include(Field field, const ParamTable<U>& table) {
    for (const auto& sub : table.entries_) {
      Entry e;
      e.spec = sub.spec;
      e.nested = sub.nested;
      if (sub.set_default) e.set_default = [field, f = sub.set_default](T& o) { f(std::invoke(field, o)); };
      if (sub.read) e.read = [field, f = sub.read](const ParamView& p, T& o) { f(p, std::invoke(field, o)); };
      if (sub.applies) e.applies = [field, f = sub.applies](const T& o) { return f(std::invoke(field, const_cast<T&>(o))); };
      push(std::move(e));
    }
    return *this;
  }

  // Every field at its default (required fields stay value-initialised).
  T defaults() const {
    T out{};
    for (const Entry& e : entries_)
      if (e.set_default) e.set_default(out);
    return out;
  }
  // Defaults, then every applicable entry read from `section` in declaration order.
  T read(const ParamView& section) const {
    T out = defaults();
    read_into(section, out);
    return out;
  }
  void read_into(const ParamView& section, T& out) const {
    for (const Entry& e : entries_) {
      if (e.applies && !e.applies(out)) continue;
      if (!e.read) continue;
      // Noted before reading, so that a failing read still leaves the row (check --resolved).
      const bool absent = !section.has(e.spec.name);
      section.note(e.spec, absent);
      if (absent && e.spec.type == "map") {
        for (ParamSpec sub : e.nested) {
          if (!sub.condition.empty()) continue;  // depends on values not given
          sub.name = e.spec.name + "." + sub.name;
          section.note(sub, true);
        }
      }
      e.read(section, out);
    }
  }
  // The declarations as documentation rows; nested tables as name.sub rows after their map row.
  std::vector<ParamSpec> specs() const {
    std::vector<ParamSpec> out;
    for (const Entry& e : entries_) {
      out.push_back(e.spec);
      for (ParamSpec sub : e.nested) {
        sub.name = e.spec.name + "." + sub.name;
        if (!e.spec.condition.empty()) sub.condition = e.spec.condition + (sub.condition.empty() ? "" : ", " + sub.condition);
        out.push_back(std::move(sub));
      }
    }
    return out;
  }
  std::vector<std::string> names() const {
    std::vector<std::string> out;
    for (const Entry& e : entries_) out.push_back(e.spec.name);
    return out;
  }

 private:
  template <class U>
  friend class ParamTable;

  struct Entry {
    ParamSpec spec;
    std::vector<ParamSpec> nested;
    std::function<void(T&)> set_default;
    Reader read;
    Predicate applies;
  };

  static Entry entry(std::string name, std::string type, std::string unit, std::string default_text,
                     const Limits& limits, std::string doc) {
    Entry e;
    e.spec.name = std::move(name);
    e.spec.type = std::move(type);
    e.spec.unit = std::move(unit);
    e.spec.default_value = std::move(default_text);
    e.spec.range = (limits.min || limits.max) ? limits.describe() : "";
    e.spec.meaning = std::move(doc);
    return e;
  }
  ParamTable& push(Entry e) {
    entries_.push_back(std::move(e));
    return *this;
  }

  template <class V, class Field>
  ParamTable& add_number(std::string name, Field field, std::string unit, std::optional<double> fallback,
                         Limits limits, std::string doc) {
    Entry e = entry(name, "number", std::move(unit), fallback ? format_param_number(*fallback) : "required", limits,
                    std::move(doc));
    if (fallback) e.set_default = [field, v = *fallback](T& o) { std::invoke(field, o) = v; };
    e.read = [field, name, limits, fallback](const ParamView& p, T& o) {
      if (fallback) {
        if (p.has(name)) std::invoke(field, o) = p.number_or(name, *fallback, limits);
      } else {
        std::invoke(field, o) = p.number(name, limits);
      }
    };
    return push(std::move(e));
  }
  template <class Field>
  ParamTable& add_integer(std::string name, Field field, std::string unit, std::optional<std::int64_t> fallback,
                          Limits limits, std::string doc) {
    using V = std::remove_reference_t<std::invoke_result_t<Field, T&>>;
    Entry e = entry(name, "integer", std::move(unit), fallback ? std::to_string(*fallback) : "required", limits,
                    std::move(doc));
    if (fallback) e.set_default = [field, v = *fallback](T& o) { std::invoke(field, o) = static_cast<V>(v); };
    e.read = [field, name, limits, fallback](const ParamView& p, T& o) {
      if (fallback) {
        if (p.has(name)) std::invoke(field, o) = static_cast<V>(p.integer_or(name, *fallback, limits));
      } else {
        std::invoke(field, o) = static_cast<V>(p.integer(name, limits));
      }
    };
    return push(std::move(e));
  }
  template <class Field, class V>
  ParamTable& add_choice(std::string name, Field field, std::vector<std::pair<std::string_view, V>> options,
                         std::optional<V> fallback, std::string doc) {
    std::string allowed, fallback_word = "required";
    std::vector<std::string_view> words;
    for (const auto& [word, value] : options) {
      allowed += (allowed.empty() ? "" : " | ") + std::string(word);
      words.push_back(word);
      if (fallback && value == *fallback) fallback_word = std::string(word);
    }
    Entry e = entry(name, "choice", "-", fallback_word, {}, std::move(doc));
    e.spec.range = allowed;
    if (fallback) e.set_default = [field, v = *fallback](T& o) { std::invoke(field, o) = v; };
    e.read = [field, name, options, words, required = !fallback](const ParamView& p, T& o) {
      if (!required && !p.has(name)) return;
      const std::string word = p.choice(name, words);
      for (const auto& [w, value] : options)
        if (w == word) std::invoke(field, o) = value;
    };
    return push(std::move(e));
  }

  std::vector<Entry> entries_;
};

}  // namespace plumage
