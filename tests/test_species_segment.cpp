// load_species_segment (species_config.hpp): a species file with its outline width replaced, as
// yaml-cpp nodes. The geometry must be the one the old text edit of the file made (the segment
// benchmarks and ladders have always measured it): width_um and, where the file sets it,
// corner_um = min(1, W/10), both written as std::to_string writes them.
#include <catch2/catch.hpp>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "plumage/species_config.hpp"
#include "test_registry.hpp"

using namespace plumage;
namespace fs = std::filesystem;

namespace {

using plumage::testing::registry;

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The species file with `key` (a line "\n    key: ..." after "\n  outline:") set to `value`.
std::string edited(std::string yaml, const std::string& key, const std::string& value) {
  const auto outline = yaml.find("\n  outline:");
  REQUIRE(outline != std::string::npos);
  const std::string line = "\n    " + key + ":";
  const auto at = yaml.find(line, outline);
  REQUIRE(at != std::string::npos);
  const auto end = yaml.find('\n', at + 1);
  yaml.replace(at, end - at, line + " " + value);
  return yaml;
}

fs::path write_beside(const fs::path& original, const std::string& name, const std::string& text) {
  // Beside the original, so relative references (crystal files) resolve alike.
  const fs::path file = original.parent_path() / name;
  std::ofstream(file) << text;
  return file;
}

void check_same_geometry(const SpeciesConfig& a, const SpeciesConfig& b) {
  for (std::uint64_t n : {0u, 3u}) {
    const CrossSection x = a.structure->generate(n), y = b.structure->generate(n);
    INFO("instance " << n);
    REQUIRE(x.top.size() == y.top.size());
    bool same = true;
    for (std::size_t i = 0; i < x.top.size(); ++i) same = same && x.top[i].x == y.top[i].x && x.top[i].z == y.top[i].z;
    CHECK(same);
    CHECK(x.regions.size() == y.regions.size());
    CHECK(x.width_nm() == y.width_nm());
  }
}

}  // namespace

TEST_CASE("load_species_segment: width and corner replaced, geometry as the text edit made it",
          "[config][species][segment]") {
  const fs::path species = fs::path(PLUMAGE_SOURCE_DIR) / "configs/species/hummingbird.yaml";
  const double width_um = 6.0;
  const SpeciesConfig segment = load_species_segment(species, width_um, registry());
  const CrossSection cs = segment.structure->generate(0);
  CHECK(cs.width_nm() == Approx(6000.0).epsilon(0.05));  // the generator's outline, not the file's 40 um

  // The old way: the file's text with both values replaced.
  std::string text = edited(read_text(species), "width_um", std::to_string(width_um));
  text = edited(text, "corner_um", std::to_string(std::min(1.0, 0.1 * width_um)));
  const fs::path copy = write_beside(species, ".plumage-test-segment-hummingbird.yaml", text);
  const SpeciesConfig expected = load_species_config(copy, registry());
  fs::remove(copy);
  check_same_geometry(segment, expected);
  CHECK(segment.species == "hummingbird");
  CHECK(segment.variant == expected.variant);
}

TEST_CASE("load_species_segment: a species without corner_um keeps its default corner", "[config][species][segment]") {
  // The rock dove's elliptic arc sets no corner_um: only its width changes.
  const fs::path species = fs::path(PLUMAGE_SOURCE_DIR) / "configs/species/rockdove.yaml";
  const SpeciesConfig segment = load_species_segment(species, 10.0, registry());
  const fs::path copy = write_beside(species, ".plumage-test-segment-rockdove.yaml",
                                     edited(read_text(species), "width_um", std::to_string(10.0)));
  const SpeciesConfig expected = load_species_config(copy, registry());
  fs::remove(copy);
  check_same_geometry(segment, expected);
}

TEST_CASE("load_species_segment: a file without an outline width is refused", "[config][species][segment]") {
  const fs::path dir = fs::temp_directory_path() / "plumage-test-segment";
  fs::create_directories(dir);
  const fs::path file = dir / "no-outline.yaml";
  std::ofstream(file) << "species: film\nnominal_stack:\n  layers: [{material: keratin, thickness_nm: 300}]\n"
                         "reflection: {model: multilayer}\n";
  CHECK_THROWS_AS(load_species_segment(file, 5.0, registry()), ConfigError);
  CHECK_THROWS_WITH(load_species_segment(file, 5.0, registry()), Catch::Contains("structure.outline.width_um"));
}
