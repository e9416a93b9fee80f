// Loading plug-in libraries (checked by plugin_probe before dlopen) and creating objects by
// (kind, type).
#include "plumage/plugin_registry.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>
#include <sstream>

#include "plumage/data_paths.hpp"
#include "plumage/version.hpp"
#include "plugin_probe.hpp"

namespace plumage {

namespace fs = std::filesystem;

namespace {

// Libraries are never unloaded before exit: objects and factories created from them may live
// anywhere, and unloading code that is still referenced is undefined behaviour.
// A library refused after dlopen stays loaded too: its static constructors have run and may have
// left references to its code behind (atexit handlers, registrations in other libraries).
std::vector<void*>& loaded_libraries() {
  static auto* libraries = new std::vector<void*>();
  return *libraries;
}

std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

class PluginRegistry::HostRegistrar final : public Registrar {
 public:
  HostRegistrar(PluginRegistry& registry, fs::path library)
      : registry_(registry), library_(std::move(library)) {}
  void add_erased(PluginInfo info, ErasedFactory factory) override {
    registry_.add(std::move(info), std::move(factory), library_);
  }

 private:
  PluginRegistry& registry_;
  fs::path library_;
};

PluginRegistry::PluginRegistry() : builtin_(std::make_unique<HostRegistrar>(*this, fs::path{})) {}

PluginRegistry::~PluginRegistry() = default;
// The built-in registrar refers to its registry, so a moved registry gets a fresh one.
PluginRegistry::PluginRegistry(PluginRegistry&& other) noexcept
    : entries_(std::move(other.entries_)),
      problems_(std::move(other.problems_)),
      builtin_(std::make_unique<HostRegistrar>(*this, fs::path{})) {}

PluginRegistry& PluginRegistry::operator=(PluginRegistry&& other) noexcept {
  entries_ = std::move(other.entries_);
  problems_ = std::move(other.problems_);
  return *this;
}

Registrar& PluginRegistry::builtin_registrar() { return *builtin_; }

std::vector<fs::path> PluginRegistry::search_path(const std::vector<fs::path>& explicit_dirs) {
  std::vector<fs::path> dirs(explicit_dirs.begin(), explicit_dirs.end());
  if (const char* env = std::getenv("PLUMAGE_PLUGIN_PATH")) {
    std::stringstream ss(env);
    for (std::string item; std::getline(ss, item, ':');) {
      if (!item.empty()) dirs.emplace_back(item);
    }
  }
  // Beside the core library first: the plug-ins built with it, also in a process that is not
  // `plumage` (python3), whose own prefix may hold another plumage.
  if (const fs::path core = core_library_path(); !core.empty())
    dirs.push_back(core.parent_path() / "plumage" / "plugins");
  try {
    dirs.push_back(executable_path().parent_path() / ".." / "lib" / "plumage" / "plugins");
  } catch (const std::exception&) {
  }
#ifdef PLUMAGE_INSTALL_PLUGIN_DIR
  dirs.emplace_back(PLUMAGE_INSTALL_PLUGIN_DIR);
#endif
  // The same folder reached twice (e.g. running the installed binary) is scanned once.
  std::vector<fs::path> unique;
  for (auto& d : dirs) {
    std::error_code ec;
    fs::path canonical = fs::weakly_canonical(d, ec);
    if (ec) canonical = d;
    if (std::find(unique.begin(), unique.end(), canonical) == unique.end()) {
      unique.push_back(canonical);
    }
  }
  return unique;
}

void PluginRegistry::load_search_path(const std::vector<fs::path>& dirs) {
  for (const auto& d : dirs) load_directory(d);
}

void PluginRegistry::load_directory(const fs::path& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return;
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("libplumage_", 0) == 0 && e.path().extension() == ".so") {
      files.push_back(e.path());
    }
  }
  std::sort(files.begin(), files.end());  // deterministic order
  for (const auto& f : files) {
    try {
      load_library(f);
    } catch (const PluginError& e) {
      problems_.push_back({f, e.what()});
    }
  }
}

void PluginRegistry::load_library(const fs::path& file) {
  std::error_code fec;
  if (!fs::exists(file, fec)) {
    throw PluginError(file.string() + ": no such plug-in library");
  }
  // dlopen maps the file as it is: a truncated or damaged file would fault inside the loader.
  if (auto problem = detail::probe_plugin_file(file)) throw PluginError(file.string() + ": " + *problem);
  // An absolute name: dlopen would search the library path for a name without a slash.
  const fs::path absolute = fs::absolute(file, fec);
  dlerror();
  void* handle = dlopen((fec ? file : absolute).c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* why = dlerror();
    throw PluginError(file.string() + ": cannot load as a shared library: " + (why ? why : "unknown reason"));
  }
  loaded_libraries().push_back(handle);
  auto follow = [&](const char* name, detail::AliasTarget kind, std::size_t size) {
    detail::AliasLookup alias = detail::follow_alias(handle, name, kind, size);
    if (!alias.target) {
      throw PluginError(file.string() + ": not a plumage plug-in: " + alias.problem +
                        " (use PLUMAGE_PLUGIN from plumage/plugin_export.hpp)");
    }
    return alias.target;
  };
  const void* abi_target = follow("plumage_abi_version", detail::AliasTarget::data, sizeof(int));
  const void* register_target = follow("plumage_register", detail::AliasTarget::code, 1);
  const int abi = *static_cast<const int*>(abi_target);
  if (abi != kAbiVersion) {
    throw PluginError(file.string() + ": plug-in ABI version " + std::to_string(abi) +
                      " does not match this plumage's ABI version " +
                      std::to_string(kAbiVersion) + "; rebuild the plug-in against this SDK");
  }
  auto* register_fn = reinterpret_cast<void (*)(Registrar&)>(const_cast<void*>(register_target));
  HostRegistrar registrar(*this, file);
  try {
    register_fn(registrar);
  } catch (const std::exception& e) {
    throw PluginError(file.string() + ": registration failed: " + e.what());
  }
}

void PluginRegistry::add(PluginInfo info, ErasedFactory factory, const fs::path& library) {
  if (const Entry* existing = find(info.kind, info.type)) {
    problems_.push_back(
        {library, info.kind + " '" + info.type + "' is shadowed by the one in " +
                      (existing->library.empty() ? std::string("core") : existing->library.string())});
    return;
  }
  entries_.push_back({std::move(info), library, std::move(factory)});
}

const PluginRegistry::Entry* PluginRegistry::find(std::string_view kind,
                                                  std::string_view type) const {
  for (const auto& e : entries_) {
    if (e.info.kind == kind && e.info.type == type) return &e;
  }
  return nullptr;
}

const PluginRegistry::Entry* PluginRegistry::find_any_kind(std::string_view type) const {
  for (const auto& e : entries_) {
    if (e.info.type == type) return &e;
  }
  return nullptr;
}

std::vector<std::string> PluginRegistry::types_of_kind(std::string_view kind) const {
  std::vector<std::string> out;
  for (const auto& e : entries_) {
    if (e.info.kind == kind) out.push_back(e.info.type);
  }
  return out;
}

PluginContext PluginRegistry::context(const fs::path& config_dir) const {
  PluginContext ctx;
  ctx.config_dir = config_dir;
  ctx.registry = this;
  return ctx;
}

namespace {

std::string unknown_type_message(const PluginRegistry& registry, std::string_view kind,
                                 std::string_view type) {
  if (const auto* other = registry.find_any_kind(type)) {
    // Appended piece by piece: GCC 12 reports a false -Wrestrict on "'" + std::string(type) here.
    std::string msg(1, '\'');
    msg.append(type).append("' is a ").append(other->info.kind).append(" plug-in, not a ").append(kind);
    return msg;
  }
  auto known = registry.types_of_kind(kind);
  std::string msg = "unknown " + std::string(kind) + " type '" + std::string(type) + "'";
  if (auto near = nearest_name(type, known)) msg += " (did you mean '" + *near + "'?)";
  if (known.empty()) {
    msg += "; no " + std::string(kind) +
           " plug-ins were found (see `plumage plugins`, --plugin-path, PLUMAGE_PLUGIN_PATH)";
  } else {
    msg += "; available: " + join(known);
  }
  return msg;
}

// One declaration per parameter (param_table.hpp), so that describe, docs and reading agree: a
// factory may read only the keys its table declares (top-level names of PluginInfo::params), and
// it must read every declared parameter that has no condition (ParamSpec::condition), present in
// the section or not (ParamTable::read does both by construction).
void check_declared(const PluginRegistry::Entry& entry, const ParamView& params, std::string_view type_key) {
  const std::vector<std::string> known = params.known_keys();
  const std::string who = entry.info.kind + " '" + entry.info.type + "' (" +
                          (entry.library.empty() ? std::string("core") : entry.library.string()) + ")";
  std::vector<std::string> declared;
  for (const ParamSpec& spec : entry.info.params) {
    const std::string top = spec.name.substr(0, spec.name.find('.'));
    declared.push_back(top);
    if (spec.condition.empty() && top == spec.name && !std::binary_search(known.begin(), known.end(), top)) {
      throw PluginError(who + " declares the parameter '" + top +
                        "' but did not read it (give it a condition in its table if it applies only sometimes)");
    }
  }
  for (const std::string& key : known) {
    if (key == type_key || std::find(declared.begin(), declared.end(), key) != declared.end()) continue;
    throw PluginError(who + " read the parameter '" + key + "', which its parameter table does not declare");
  }
}

}  // namespace

std::unique_ptr<PluginObject> PluginRegistry::create_erased(std::string_view kind,
                                                            const ParamView& section,
                                                            std::string_view type_key,
                                                            const PluginContext& context) const {
  const std::string type = section.text(type_key);
  const Entry* entry = find(kind, type);
  if (!entry) section.fail(type_key, unknown_type_message(*this, kind, type));
  auto object = entry->factory(section, context);
  check_declared(*entry, section, type_key);
  section.finish();
  return object;
}

std::unique_ptr<PluginObject> PluginRegistry::create_named_erased(
    std::string_view kind, std::string_view type, const ParamView& params,
    const PluginContext& context) const {
  const Entry* entry = find(kind, type);
  if (!entry) throw PluginError(unknown_type_message(*this, kind, type));
  auto object = entry->factory(params, context);
  check_declared(*entry, params, {});
  params.finish();
  return object;
}

}  // namespace plumage
