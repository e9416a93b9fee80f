// Species configs: the shipped ones validate; bad ones fail at the right line.
#include <catch2/catch.hpp>

#include <fstream>

#include "plumage/species_config.hpp"
#include "test_registry.hpp"

using namespace plumage;
namespace fs = std::filesystem;

namespace {

using plumage::testing::registry;

fs::path write_temp(const std::string& name, const std::string& text) {
  fs::path dir = fs::temp_directory_path() / "plumage-test-species";
  fs::create_directories(dir);
  fs::path file = dir / name;
  std::ofstream(file) << text;
  return file;
}

const char* kGood =
    "species: twofilm\n"
    "common_name: Two-film test bird\n"
    "variant: thin\n"
    "variants:\n"
    "  thin: {}\n"
    "  thick:\n"
    "    nominal_stack: {layers: [{material: keratin, thickness_nm: 600}]}\n"
    "nominal_stack:\n"
    "  layers: [{material: keratin, thickness_nm: 300}]\n"
    "reflection: {model: multilayer}\n";

}  // namespace

TEST_CASE("every shipped species config validates, in every variant", "[config][species]") {
  int count = 0;
  for (const auto& e : fs::directory_iterator(fs::path(PLUMAGE_SOURCE_DIR) / "configs" / "species")) {
    if (e.path().extension() != ".yaml") continue;
    INFO(e.path());
    auto variants = species_variants(e.path());
    if (variants.empty()) variants.push_back("");
    for (const auto& v : variants) CHECK_NOTHROW(load_species_config(e.path(), registry(), v));
    ++count;
  }
  CHECK(count >= 4);
}

TEST_CASE("variants deep-merge over the base document", "[config][species]") {
  auto file = write_temp("twofilm.yaml", kGood);
  auto thin = load_species_config(file, registry());
  CHECK(thin.variant == "thin");
  CHECK(thin.nominal_stack->layers.at(0).thickness_nm == 300.0);
  auto thick = load_species_config(file, registry(), "thick");
  CHECK(thick.nominal_stack->layers.at(0).thickness_nm == 600.0);
  CHECK(thick.reflection != nullptr);
  CHECK_THROWS_WITH(load_species_config(file, registry(), "thick_"), Catch::Contains("did you mean 'thick'?"));
}

TEST_CASE("species config errors name file:line and the nearest name", "[config][species]") {
  std::string bad_model = kGood;
  bad_model.replace(bad_model.find("model: multilayer"), 17, "model: multilayr");
  auto file = write_temp("badmodel.yaml", bad_model);
  CHECK_THROWS_WITH(load_species_config(file, registry()),
                    Catch::Contains("badmodel.yaml:10:21: reflection.model: unknown local_reflection type 'multilayr' (did you mean 'multilayer'?)"));

  auto typo = write_temp("typo.yaml", std::string(kGood) + "reflction: 1\n");
  CHECK_THROWS_WITH(load_species_config(typo, registry()),
                    Catch::Contains("typo.yaml:11:1: reflction: unknown key 'reflction' (did you mean 'reflection'?)"));

  auto param = write_temp("param.yaml", std::string(kGood).replace(std::string(kGood).find("{model: multilayer}"), 19, "{model: multilayer, order: 2}"));
  CHECK_THROWS_WITH(load_species_config(param, registry()),
                    Catch::Contains("param.yaml:10:") && Catch::Contains("unknown key 'order'"));

  auto neg = write_temp("neg.yaml", std::string(kGood).replace(std::string(kGood).find("thickness_nm: 300"), 17, "thickness_nm: -300"));
  CHECK_THROWS_WITH(load_species_config(neg, registry()), Catch::Contains("neg.yaml:9:") && Catch::Contains("out of range"));

  CHECK_THROWS_WITH(load_species_config("/no/such/species.yaml", registry()), Catch::StartsWith("/no/such/species.yaml: no such file"));
}
