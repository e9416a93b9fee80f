// The plug-in contract seen from a plug-in: what it registers and what its factories receive.
//
// A plug-in is a shared library libplumage_<name>.so that exports exactly two aliases (see
// plugin_export.hpp): plumage_abi_version and plumage_register. plumage_register receives a
// Registrar and adds one factory per (kind, type) it provides. Kinds are the extension points
// of core/include/plumage/ (each interface names its kind in `plugin_kind`).
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "plumage/params.hpp"

namespace plumage {

class PluginRegistry;

// Base of every object a plug-in creates (its library stays loaded while objects exist).
class PluginObject {
 public:
  virtual ~PluginObject() = default;
};

// One row of a parameter table (param_table.hpp builds them from the declarations), printed by
// `plumage plugins describe <type>` and docs/parameters.md.
struct ParamSpec {
  std::string name{};           // dotted for nested maps: "outline.width_um"
  std::string type{};           // number, integer, text, bool, choice, interval, list, map, material...
  std::string unit{};           // nm, um, deg, 1 ... ("-" when dimensionless)
  std::string default_value{};  // "required" when there is no default
  std::string meaning{};
  std::string range{};          // "> 0", "in [0, 1]", "dense | gmres"; empty when unbounded
  std::string condition{};      // when the parameter applies ("model: films"); empty: always
};

// Default member initialisers so that registrations name only what they set (designated
// initialisers without `.kind`, which Registrar::add fills in).
struct PluginInfo {
  std::string kind{};     // filled from the interface by Registrar::add
  std::string type{};     // the name a config uses, e.g. "multilayer"
  std::string version{};  // the plug-in's own version
  std::string summary{};  // one line
  std::vector<ParamSpec> params{};
};

// What a factory may need besides its parameters.
struct PluginContext {
  std::filesystem::path config_dir;  // relative file names in configs resolve against this
  std::filesystem::path cache_dir;   // where derived data (tables...) may be cached
  const PluginRegistry* registry = nullptr;  // to create nested plug-ins by kind and type
};

using ErasedFactory =
    std::function<std::unique_ptr<PluginObject>(const ParamView&, const PluginContext&)>;

class Registrar {
 public:
  virtual ~Registrar() = default;

  // Registers a factory for interface I. F: (const ParamView&, const PluginContext&) ->
  // std::unique_ptr<T> with T derived from I.
  template <class I, class F>
  void add(PluginInfo info, F factory) {
    info.kind = std::string(I::plugin_kind);
    add_erased(std::move(info),
               [f = std::move(factory)](const ParamView& params, const PluginContext& ctx)
                   -> std::unique_ptr<PluginObject> {
                 std::unique_ptr<I> object = f(params, ctx);
                 return std::unique_ptr<PluginObject>(std::move(object));
               });
  }

  virtual void add_erased(PluginInfo info, ErasedFactory factory) = 0;
};

}  // namespace plumage
