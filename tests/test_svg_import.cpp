// Cross sections from SVG (issue 25 (c)): a flat film traced as two rects (keratin 500 nm over
// melanin 100 nm) gives the layered model of that film, the far field of the same film built by
// validation_shape `slab`, and the far field of the approximate-solver tests' strip; bad files
// are refused with InputFileError naming the element.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "plumage/cross_section_io.hpp"
#include "plumage/input_file.hpp"
#include "plumage/simulation.hpp"
#include "plumage/species_config.hpp"
#include "plumage/structure_generator.hpp"
#include "solver/approximate_solver.hpp"
#include "test_registry.hpp"

using namespace plumage;
namespace fs = std::filesystem;

namespace {

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "plumage-test-svg-import" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void write_text(const fs::path& file, const std::string& text) { std::ofstream(file, std::ios::binary) << text; }

// A 6 µm wide film in SVG units of 1 nm, as an editor writes it (y down: the top at y = 0).
std::string film_svg(const std::string& melanin_element) {
  return "<?xml version=\"1.0\"?>\n"
         "<!-- traced over a TEM image -->\n"
         "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 6000 600\">\n"
         "  <image href=\"tem.png\" width=\"6000\" height=\"600\"/>\n"
         "  <rect id=\"cortex\" x=\"0\" y=\"0\" width=\"6000\" height=\"600\" style=\"fill:#CCCCCC;stroke:none\"/>\n"
         "  " + melanin_element + "\n"
         "</svg>\n";
}

const std::string kMelaninPath = "<path id=\"film\" fill=\"#000000\" d=\"M 0,500 h 6000 v 100 H 0 z\"/>";

SvgImportOptions film_options() {
  SvgImportOptions o;
  o.um_per_unit = 0.001;
  o.materials = {{"#cccccc", Material::keratin()}, {"#000000", Material::melanin()}};
  o.max_segment_nm = 30.0;
  return o;
}

class FixedReflection final : public LocalReflection {
 public:
  void reflect(std::span<const Request> requests, std::span<JonesReflection> out) const override {
    for (std::size_t i = 0; i < requests.size(); ++i) out[i] = {Complex{-0.3, 0.1}, 0.0, 0.0, Complex{0.25, 0.05}};
  }
};

double worst_difference(const FarField& a, const FarField& b) {
  double worst = 0.0, scale = 0.0;
  for (int pol = 0; pol < 2; ++pol) {
    REQUIRE(a.field[pol].size() == b.field[pol].size());
    for (std::size_t d = 0; d < a.field[pol].size(); ++d) {
      for (int c = 0; c < 3; ++c) {
        scale = std::max(scale, std::abs(a.field[pol][d][c]));
        worst = std::max(worst, std::abs(a.field[pol][d][c] - b.field[pol][d][c]));
      }
    }
  }
  REQUIRE(scale > 0.0);
  return worst / scale;
}

}  // namespace

TEST_CASE("svg import: a flat film gives the film's layered model and regions", "[svg-import]") {
  const CrossSection cs = parse_svg_cross_section(film_svg(kMelaninPath), "film.svg", film_options());
  CHECK(validate(cs).empty());
  REQUIRE(cs.regions.size() == 2);
  CHECK(cs.regions[0].material.kind() == Material::Kind::keratin);
  CHECK(cs.regions[1].material.kind() == Material::Kind::melanin);
  CHECK(cs.regions[1].parent == 0);
  CHECK(cs.top.front().x == -3000.0);
  CHECK(cs.top.back().x == 3000.0);
  CHECK(cs.top.size() == 201);  // 6000 nm in edges of at most 30 nm
  REQUIRE(cs.layered);
  const LayerProfile p = layer_profile_at(cs, cs.top.size() / 2);
  REQUIRE(p.layers.size() == 2);
  CHECK(p.layers[0].material.kind() == Material::Kind::keratin);
  CHECK(p.layers[0].thickness_nm == Approx(500.0).epsilon(1e-12));
  CHECK(p.layers[1].material.kind() == Material::Kind::melanin);
  CHECK(p.layers[1].thickness_nm == Approx(100.0).epsilon(1e-12));
  CHECK(p.substrate.kind() == Material::Kind::air);

  // The same film as a polygon with a scale bar instead of um_per_unit: the same section.
  SvgImportOptions bar = film_options();
  bar.um_per_unit.reset();
  bar.scale_bar_um = 2.0;
  std::string text = film_svg("<polygon id=\"film\" fill=\"#000000\" points=\"0,500 6000,500 6000,600 0,600\"/>");
  text.insert(text.find("</svg>"), "<line id=\"scale_bar\" x1=\"100\" y1=\"50\" x2=\"2100\" y2=\"50\"/>\n");
  const CrossSection b = parse_svg_cross_section(text, "bar.svg", bar);
  REQUIRE(b.layered);
  const LayerProfile q = layer_profile_at(b, b.top.size() / 2);
  REQUIRE(q.layers.size() == 2);
  CHECK(q.layers[0].thickness_nm == Approx(500.0).epsilon(1e-12));
  CHECK(q.layers[1].thickness_nm == Approx(100.0).epsilon(1e-12));
}

TEST_CASE("svg import: the film's far field is the strip's and validation_shape slab's", "[svg-import]") {
  const fs::path dir = scratch("film");
  write_text(dir / "film-0.svg", film_svg(kMelaninPath));
  write_text(dir / "svg.yaml",
             "species: svg-film\nreflection: {model: multilayer}\n"
             "structure:\n  generator: svg_file\n  files: \"film-{index}.svg\"\n  um_per_unit: 0.001\n"
             "  max_segment_nm: 30\n  materials: {\"#cccccc\": keratin, \"#000000\": melanin}\n");
  write_text(dir / "slab.yaml",
             "species: slab-film\nreflection: {model: multilayer}\n"
             "structure:\n  generator: validation_shape\n  shape: slab\n  width_um: 6\n  spacing_nm: 30\n"
             "  stack:\n    layers:\n      - {material: keratin, thickness_nm: 500}\n"
             "      - {material: melanin, thickness_nm: 100}\n    substrate: air\n");
  const SpeciesConfig svg = load_species_config(dir / "svg.yaml", testing::registry());
  const SpeciesConfig slab = load_species_config(dir / "slab.yaml", testing::registry());
  const CrossSection cs = svg.structure->generate(0);
  CHECK(cs.generator == "svg_file");

  SimulationRequest request;
  request.lambdas_nm = {450.0, 600.0};
  request.theta_deg = {20.0};
  request.instances = 1;
  const FarFieldSet a = simulate(svg, request), b = simulate(slab, request);
  REQUIRE(a.units.size() == b.units.size());
  REQUIRE(a.units.size() == 2);
  for (std::size_t u = 0; u < a.units.size(); ++u) {
    const double d = worst_difference(a.units[u].instances.at(0), b.units[u].instances.at(0));
    WARN("svg film against validation_shape slab, unit " << u << ": relative difference " << d);
    CHECK(d <= 1e-12);
  }

  // The strip of test_approximate_solver.cpp: a flat top of 30 nm edges under fixed coefficients.
  CrossSection strip;
  for (int k = 0; k <= 200; ++k) strip.top.push_back({-3000.0 + 6000.0 * k / 200, 0.0});
  const ApproximateSolver solver(ApproximateSolver::Currents::reflected, 0.25);
  const auto reflection = std::make_shared<FixedReflection>();
  const std::vector<double> phi_o = {deg_to_rad(-20.0), deg_to_rad(0.0), deg_to_rad(20.0), deg_to_rad(35.0)};
  const double phis[1] = {deg_to_rad(20.0)};
  const FarField fs_svg = solver.solve(*solver.prepare(cs, reflection), 550.0, deg_to_rad(20.0), phis, phi_o).front();
  const FarField fs_strip = solver.solve(*solver.prepare(strip, reflection), 550.0, deg_to_rad(20.0), phis, phi_o).front();
  const double d = worst_difference(fs_svg, fs_strip);
  WARN("svg film against the strip: relative difference " << d);
  CHECK(d <= 1e-12);
}

namespace {

void check_refused(const std::string& text, const SvgImportOptions& options, const std::string& expected) {
  try {
    parse_svg_cross_section(text, "bad.svg", options);
    FAIL("no error for " << expected);
  } catch (const InputFileError& e) {
    CHECK(e.file() == "bad.svg");
    CHECK_THAT(e.what(), Catch::Contains(expected));
  }
}

}  // namespace

TEST_CASE("svg import: bad files are refused naming the element", "[svg-import]") {
  const SvgImportOptions o = film_options();
  check_refused(film_svg("<path id=\"film\" fill=\"#000000\" d=\"M 0,500 h 6000 v 100 H 0\"/>"), o,
                "element 'film' (line 6): open outline");
  check_refused(film_svg("<path id=\"blob\" fill=\"#112233\" d=\"M 0,500 h 6000 v 100 H 0 z\"/>"), o,
                "element 'blob' (line 6): no material for fill '#112233'");
  check_refused(film_svg("<path id=\"curvy\" fill=\"#000000\" d=\"M 0,500 C 10,10 20,20 6000,500 z\"/>"), o,
                "element 'curvy' (line 6): path command 'C' is not supported");
  check_refused(film_svg("<path id=\"two\" fill=\"#000000\" d=\"M 0,500 L 10,510\"/>"), o,
                "element 'two' (line 6): open outline");
  check_refused(film_svg("<polygon id=\"thin\" fill=\"#000000\" points=\"0,500 10,510 0,500\"/>"), o,
                "element 'thin' (line 6): an outline needs at least 3 points");
  check_refused(film_svg("<rect id=\"moved\" fill=\"#000000\" transform=\"translate(1,2)\" width=\"1\" height=\"1\"/>"), o,
                "element 'moved' (line 6): transforms are not supported");
  SvgImportOptions no_scale = o;
  no_scale.um_per_unit.reset();
  check_refused(film_svg(kMelaninPath), no_scale, "no scale");
  // Mis-scaled (a 10 m wide outline at 10 nm edges): refused before any vertex is made.
  check_refused(film_svg("<rect id=\"huge\" fill=\"#000000\" x=\"0\" y=\"500\" width=\"1e10\" height=\"100\"/>"), o,
                "would need over 1e7 vertices");
  // A self-intersecting outline is read, and reported by validate() as any section's.
  const CrossSection bow = parse_svg_cross_section(
      film_svg("<polygon id=\"film\" fill=\"#000000\" points=\"100,500 5900,590 5900,500 100,590\"/>"), "bow.svg", o);
  CHECK_FALSE(validate(bow).empty());
}

TEST_CASE("svg import: inner regions that are not layers give no layered model", "[svg-import]") {
  const CrossSection cs = parse_svg_cross_section(
      film_svg("<polygon id=\"granule\" fill=\"#000000\" points=\"2900,200 3100,200 3100,300 2900,300\"/>"),
      "granule.svg", film_options());
  CHECK_FALSE(cs.layered);
  CHECK_THAT(cs.label, Catch::Contains("no layered model") && Catch::Contains("granule"));
  REQUIRE(cs.regions.size() == 2);
  CHECK(cs.regions[1].role == RegionRole::melanosome);
  CHECK(validate(cs).empty());
}

TEST_CASE("svg import: relative commands, id prefixes and nesting", "[svg-import]") {
  SvgImportOptions o = film_options();
  // The longest id prefix wins over a shorter one and over the fill.
  o.materials.push_back({"air", Material::air()});
  o.materials.push_back({"air-in-melanin", Material::keratin()});
  const std::string text = film_svg(
      "<path id=\"granule\" fill=\"#000000\" d=\"m 2800,100 l 400,0 0,300 -400,0 Z\"/>\n"
      "<polygon id=\"air-1\" fill=\"#000000\" points=\"2900,200 3100,200 3100,300 2900,300\"/>\n"
      "<polygon id=\"air-in-melanin-2\" fill=\"#000000\" points=\"2950,220 3000,220 3000,260 2950,260\"/>");
  const CrossSection cs = parse_svg_cross_section(text, "nested.svg", o);
  REQUIRE(cs.regions.size() == 4);
  CHECK(cs.regions[1].material.kind() == Material::Kind::melanin);  // granule, by fill
  CHECK(cs.regions[2].material.kind() == Material::Kind::air);      // air-1
  CHECK(cs.regions[3].material.kind() == Material::Kind::keratin);  // air-in-melanin-2
  CHECK(cs.regions[1].parent == 0);
  CHECK(cs.regions[2].parent == 1);
  CHECK(cs.regions[3].parent == 2);
  // m/l relative to the current point: the granule spans x 2800..3200, y 100..400 (z −100..−400).
  double x_min = 1e9, x_max = -1e9, z_min = 1e9, z_max = -1e9;
  for (const Vec2& v : cs.regions[1].outline) {
    x_min = std::min(x_min, v.x), x_max = std::max(x_max, v.x);
    z_min = std::min(z_min, v.z), z_max = std::max(z_max, v.z);
  }
  CHECK(x_min == -200.0);
  CHECK(x_max == 200.0);
  CHECK(z_min == -400.0);
  CHECK(z_max == -100.0);
  CHECK(signed_area(cs.regions[1].outline) > 0.0);
  CHECK(validate(cs).empty());
}
