// Host side of the plug-in system: finds libraries, checks their ABI, keeps them loaded, and
// creates objects by (kind, type).
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "plumage/error.hpp"
#include "plumage/params.hpp"
#include "plumage/plugin.hpp"

namespace plumage {

class PluginRegistry {
 public:
  struct Entry {
    PluginInfo info;
    std::filesystem::path library;  // empty for types built into core
    ErasedFactory factory;
  };

  // A library that could not be used while scanning a folder (scans never throw).
  struct Problem {
    std::filesystem::path library;
    std::string message;
  };

  PluginRegistry();
  ~PluginRegistry();
  PluginRegistry(PluginRegistry&&) noexcept;
  PluginRegistry& operator=(PluginRegistry&&) noexcept;

  // The folders searched, in order: explicit ones (--plugin-path), $PLUMAGE_PLUGIN_PATH
  // (colon-separated), <folder of libplumage_core.so>/plumage/plugins (also right in python3,
  // which is not our executable), <folder of the executable>/../lib/plumage/plugins, and
  // <install prefix>/lib/plumage/plugins. Never the current directory implicitly.
  static std::vector<std::filesystem::path> search_path(
      const std::vector<std::filesystem::path>& explicit_dirs);

  // Loads every libplumage_*.so in each folder, in order. The first registration of a
  // (kind, type) wins; later ones are recorded as problems ("shadowed").
  void load_search_path(const std::vector<std::filesystem::path>& dirs);
  void load_directory(const std::filesystem::path& dir);
  // Loads one library; throws PluginError (missing file, not a library, missing symbol,
  // ABI mismatch, registration failure).
  void load_library(const std::filesystem::path& file);

  // Registers types provided by core itself.
  Registrar& builtin_registrar();

  const std::vector<Entry>& entries() const { return entries_; }
  const std::vector<Problem>& problems() const { return problems_; }
  const Entry* find(std::string_view kind, std::string_view type) const;
  const Entry* find_any_kind(std::string_view type) const;
  std::vector<std::string> types_of_kind(std::string_view kind) const;

  // Creates an object of interface I from a config section: the type name is read from
  // section[type_key]; the rest of the section is the object's parameters. Unknown type, a type
  // of another kind, or unknown parameters afterwards are ConfigErrors at the right line.
  template <class I>
  std::unique_ptr<I> create(const ParamView& section, std::string_view type_key,
                            const PluginContext& context) const {
    return cast<I>(create_erased(I::plugin_kind, section, type_key, context));
  }

  // Creates an object by type name with parameters from `params` (e.g. ParamView{} for none).
  template <class I>
  std::unique_ptr<I> create_named(std::string_view type, const ParamView& params,
                                  const PluginContext& context) const {
    return cast<I>(create_named_erased(I::plugin_kind, type, params, context));
  }

  // A context pointing at this registry.
  PluginContext context(const std::filesystem::path& config_dir = {}) const;

 private:
  class HostRegistrar;

  std::unique_ptr<PluginObject> create_erased(std::string_view kind, const ParamView& section,
                                              std::string_view type_key,
                                              const PluginContext& context) const;
  std::unique_ptr<PluginObject> create_named_erased(std::string_view kind, std::string_view type,
                                                    const ParamView& params,
                                                    const PluginContext& context) const;
  void add(PluginInfo info, ErasedFactory factory, const std::filesystem::path& library);

  template <class I>
  static std::unique_ptr<I> cast(std::unique_ptr<PluginObject> object) {
    auto* typed = dynamic_cast<I*>(object.get());
    if (!typed) throw PluginError("plug-in factory returned an object of the wrong interface");
    object.release();
    return std::unique_ptr<I>(typed);
  }

  std::vector<Entry> entries_;
  std::vector<Problem> problems_;
  std::unique_ptr<HostRegistrar> builtin_;
};

}  // namespace plumage
