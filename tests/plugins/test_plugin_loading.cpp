// Every way a plug-in can be refused gives a clear PluginError, never a crash.
#include <catch2/catch.hpp>

#include <algorithm>

#include "hostile_plugins.hpp"
#include "plumage/config_document.hpp"
#include "plumage/data_paths.hpp"
#include "plumage/local_reflection.hpp"
#include "plumage/plugin_registry.hpp"
#include "plumage/version.hpp"

using namespace plumage;
namespace fs = std::filesystem;

namespace {
fs::path fixture(const std::string& name) { return fs::path(FIXTURE_DIR) / ("libplumage_fixture_" + name + ".so"); }
}  // namespace

TEST_CASE("a good plug-in registers and creates objects", "[plugins]") {
  PluginRegistry registry;
  registry.load_library(fixture("good"));
  const auto* entry = registry.find("local_reflection", "fixture_constant");
  REQUIRE(entry != nullptr);
  CHECK(entry->library == fixture("good"));
  CHECK(entry->info.params.size() == 1);
  auto doc = ConfigDocument::parse("reflection: {model: fixture_constant, amplitude: 0.25}\n", "c.yaml");
  auto model = registry.create<LocalReflection>(doc.root().child("reflection"), "model", registry.context());
  LayerProfile p;
  CHECK(model->reflect_one({500.0, {}, &p}).ss == Complex(0.25, 0.0));
}

TEST_CASE("wrong ABI is refused naming the file and both versions", "[plugins]") {
  PluginRegistry registry;
  CHECK_THROWS_AS(registry.load_library(fixture("badabi")), PluginError);
  CHECK_THROWS_WITH(registry.load_library(fixture("badabi")),
                    Catch::Contains("libplumage_fixture_badabi.so") &&
                        Catch::Contains("ABI version " + std::to_string(kAbiVersion + 100)) &&
                        Catch::Contains("ABI version " + std::to_string(kAbiVersion)));
  CHECK(registry.entries().empty());
}

TEST_CASE("a library without the aliases is refused", "[plugins]") {
  PluginRegistry registry;
  CHECK_THROWS_WITH(registry.load_library(fixture("nosymbol")),
                    Catch::Contains("not a plumage plug-in") && Catch::Contains("plumage_abi_version"));
}

TEST_CASE("a missing or non-ELF library is refused", "[plugins]") {
  PluginRegistry registry;
  CHECK_THROWS_WITH(registry.load_library("/no/such/libplumage_x.so"), Catch::Contains("no such plug-in library"));
  CHECK_THROWS_WITH(registry.load_library(fs::path(FIXTURE_DIR) / "libplumage_notalibrary.so"),
                    Catch::Contains("libplumage_notalibrary.so: not an ELF shared object"));
}

TEST_CASE("an ABI symbol that is not the PLUMAGE_PLUGIN alias is refused, not followed", "[plugins]") {
  PluginRegistry registry;
  // A plain int: read as the alias's pointer it would be an address near zero.
  CHECK_THROWS_WITH(registry.load_library(fixture("plainint")),
                    Catch::Contains("libplumage_fixture_plainint.so: not a plumage plug-in") &&
                        Catch::Contains("'plumage_abi_version' is a 4-byte object, not the 8-byte alias"));
  // Pointer-sized like the alias, but pointing at no object of the library.
  CHECK_THROWS_WITH(registry.load_library(fixture("wildalias")),
                    Catch::Contains("libplumage_fixture_wildalias.so: not a plumage plug-in") &&
                        Catch::Contains("'plumage_abi_version' points outside this library's readable data"));
  CHECK(registry.entries().empty());
}

namespace {
fs::path real_plugin() { return fs::path(PLUMAGE_TEST_PLUGIN_DIR) / "libplumage_multilayer.so"; }
}  // namespace

TEST_CASE("a scan survives truncated, garbage and mistyped files and lists each as a problem", "[plugins][hostile]") {
  const auto folder = plumage::testing::make_hostile_plugin_folder(
      fs::temp_directory_path() / "plumage-test-plugin-loading" / "hostile", real_plugin(), fixture("good"),
      fixture("plainint"));
  PluginRegistry registry;
  CHECK_NOTHROW(registry.load_directory(folder.dir));
  REQUIRE(registry.find("local_reflection", "fixture_constant") != nullptr);
  CHECK(registry.find("local_reflection", "fixture_constant")->library == folder.dir / "libplumage_good.so");
  CHECK(registry.entries().size() == 2);  // the good fixture's two types, nothing from a bad file
  CHECK(registry.problems().size() == folder.bad.size());
  for (const auto& bad : folder.bad) {
    INFO(bad.name);
    const fs::path file = folder.dir / bad.name;
    const auto problem = std::find_if(registry.problems().begin(), registry.problems().end(),
                                      [&](const auto& p) { return p.library == file; });
    REQUIRE(problem != registry.problems().end());
    CHECK_THAT(problem->message, Catch::StartsWith(file.string() + ": ") && Catch::Contains(bad.reason));
    // Asked for by name, the same file is a PluginError naming it (the command's exit 2).
    PluginRegistry alone;
    CHECK_THROWS_WITH(alone.load_library(file), Catch::StartsWith(file.string() + ": ") && Catch::Contains(bad.reason));
  }
}

TEST_CASE("a plug-in without section headers is still accepted: the loader never reads them", "[plugins][hostile]") {
  const fs::path dir = fs::temp_directory_path() / "plumage-test-plugin-loading" / "no-sections";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::string bytes = plumage::testing::read_bytes(real_plugin());
  Elf64_Ehdr header;
  std::memcpy(&header, bytes.data(), sizeof header);
  header.e_shoff = 0;
  header.e_shnum = 0;
  header.e_shstrndx = 0;
  std::memcpy(bytes.data(), &header, sizeof header);
  plumage::testing::write_bytes(dir / "libplumage_multilayer.so", bytes);
  PluginRegistry registry;
  CHECK_NOTHROW(registry.load_library(dir / "libplumage_multilayer.so"));
  CHECK(registry.find("local_reflection", "multilayer") != nullptr);
}

TEST_CASE("a registration that throws is reported", "[plugins]") {
  PluginRegistry registry;
  CHECK_THROWS_WITH(registry.load_library(fixture("throws")), Catch::Contains("registration failed: fixture refuses"));
}

TEST_CASE("wrong kind and unknown types are config errors at the line", "[plugins]") {
  PluginRegistry registry;
  registry.load_library(fixture("good"));
  auto doc = ConfigDocument::parse("a: {model: fixture_other}\nb: {model: fixture_constnt}\n", "k.yaml");
  CHECK_THROWS_WITH(registry.create<LocalReflection>(doc.root().child("a"), "model", registry.context()),
                    Catch::StartsWith("k.yaml:1:12: a.model: 'fixture_other' is a fixture_kind plug-in, not a local_reflection"));
  CHECK_THROWS_WITH(registry.create<LocalReflection>(doc.root().child("b"), "model", registry.context()),
                    Catch::Contains("did you mean 'fixture_constant'?"));
  CHECK_THROWS_AS(registry.create_named<LocalReflection>("fixture_other", ParamView{}, registry.context()), PluginError);
}

TEST_CASE("scanning a folder records problems and keeps the good plug-ins", "[plugins]") {
  PluginRegistry registry;
  CHECK_NOTHROW(registry.load_directory(FIXTURE_DIR));
  CHECK(registry.find("local_reflection", "fixture_constant") != nullptr);
  CHECK(registry.problems().size() == 6);  // badabi, nosymbol, throws, notalibrary, plainint, wildalias
  // A second folder registering the same type is shadowed, first one wins.
  registry.load_directory(FIXTURE_DIR);
  CHECK(registry.entries().size() == 2);
}

TEST_CASE("search path order: explicit, environment, beside the core library, beside the executable, prefix",
          "[plugins]") {
  ::setenv("PLUMAGE_PLUGIN_PATH", "/env/one:/env/two", 1);
  auto dirs = PluginRegistry::search_path({"/explicit"});
  ::unsetenv("PLUMAGE_PLUGIN_PATH");
  REQUIRE(dirs.size() >= 4);
  CHECK(dirs[0] == "/explicit");
  CHECK(dirs[1] == "/env/one");
  CHECK(dirs[2] == "/env/two");
  // The test program links libplumage_core.so from <build>/lib: its plug-in folder comes first.
  CHECK(dirs[3] == std::filesystem::weakly_canonical(core_library_path().parent_path() / "plumage" / "plugins"));
  CHECK(dirs[3].string().ends_with("lib/plumage/plugins"));
}

namespace {

// A local_reflection built into the test that reads `read` and declares `declared`.
class Constant final : public LocalReflection {
 public:
  void reflect(std::span<const Request> requests, std::span<JonesReflection> out) const override {
    for (std::size_t i = 0; i < requests.size(); ++i) out[i] = {};
  }
};

void add_builtin(PluginRegistry& registry, const std::string& type, std::vector<ParamSpec> declared,
                 std::vector<std::string> read) {
  registry.builtin_registrar().add<LocalReflection>(
      {.type = type, .version = "1", .summary = "test", .params = std::move(declared)},
      [read](const ParamView& p, const PluginContext&) {
        for (const auto& key : read) p.number_or(key, 1.0);
        return std::make_unique<Constant>();
      });
}

}  // namespace

TEST_CASE("a factory reads exactly the parameters its table declares", "[plugins][param-table]") {
  PluginRegistry registry;
  add_builtin(registry, "reads_undeclared", {{"a", "number", "1", "1", "declared"}}, {"a", "b"});
  add_builtin(registry, "skips_declared", {{"a", "number", "1", "1", "declared"}, {"b", "number", "1", "1", "x"}}, {"a"});
  ParamSpec conditional{"b", "number", "1", "1", "only for films"};
  conditional.condition = "model: films";
  add_builtin(registry, "conditional", {{"a", "number", "1", "1", "declared"}, conditional}, {"a"});
  add_builtin(registry, "nested", {{"a", "map", "-", "{}", "a map"}, {"a.x", "number", "1", "1", "in a"}}, {"a"});
  // A fresh empty section per creation: a view remembers the keys read from it.
  auto none = [] { return ConfigDocument::parse("{}\n", "empty.yaml"); };
  CHECK_THROWS_WITH(registry.create_named<LocalReflection>("reads_undeclared", none().root(), registry.context()),
                    Catch::Contains("read the parameter 'b', which its parameter table does not declare"));
  CHECK_THROWS_WITH(registry.create_named<LocalReflection>("skips_declared", none().root(), registry.context()),
                    Catch::Contains("declares the parameter 'b' but did not read it"));
  CHECK_NOTHROW(registry.create_named<LocalReflection>("conditional", none().root(), registry.context()));
  CHECK_NOTHROW(registry.create_named<LocalReflection>("nested", none().root(), registry.context()));
  // Through a config section the type key is the host's, not the factory's.
  auto doc = ConfigDocument::parse("reflection: {model: conditional, a: 2}\n", "c.yaml");
  CHECK_NOTHROW(registry.create<LocalReflection>(doc.root().child("reflection"), "model", registry.context()));
}
