// Cross sections from FeatherLab's per-instance text files (issue 25 (b)): a flat four-layer
// barbule written by hand in that format gives, at every top vertex, the layer stack it was
// written with (thicknesses from the curves' heights, the melanin fraction of the file) and the
// far field of the same stack built by validation_shape `slab`; a
// procedural rock dove instance (layered_barbule granule_gap) and procedural starling and
// bronzewing instances (melanosome_rows, FeatherLab's starling layout of curves) written in that
// format give their own layer profiles back at every node; the featherlab_files generator reads file n + 1 for
// instance n; damaged files are refused with InputFileError naming the file, the line and the
// field.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "plumage/featherlab_section.hpp"
#include "plumage/input_file.hpp"
#include "plumage/simulation.hpp"
#include "plumage/species_config.hpp"
#include "plumage/structure_generator.hpp"
#include "test_registry.hpp"

using namespace plumage;
namespace fs = std::filesystem;

namespace {

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "plumage-test-featherlab-import" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void write_text(const fs::path& file, const std::string& text) { std::ofstream(file, std::ios::binary) << text; }

// Curves (nm) in FeatherLab's layout: xyvals "x,y" in µm, info "start,count".
FeatherLabTexts featherlab_texts(const std::vector<Polyline>& curves, const std::vector<double>& ratio) {
  FeatherLabTexts t;
  std::ostringstream xy, info, mr;
  xy << std::setprecision(17);
  mr << std::setprecision(17);
  std::size_t start = 0;
  for (const Polyline& c : curves) {
    info << start << ',' << c.size() << '\n';
    for (const Vec2& v : c) xy << v.x / 1000.0 << ',' << v.z / 1000.0 << '\n';
    start += c.size();
  }
  for (double f : ratio) mr << f << '\n';
  t.xyvals = xy.str();
  t.info = info.str();
  t.melanin_ratio = mr.str();
  t.xyvals_name = "xyvals1.txt";
  t.info_name = "info1.txt";
  t.melanin_ratio_name = "melaninRatio1.txt";
  return t;
}

void write_instance(const fs::path& dir, int number, const FeatherLabTexts& t) {
  const FeatherLabFiles f = featherlab_files_of(dir, static_cast<std::uint64_t>(number));
  write_text(f.xyvals, t.xyvals);
  write_text(f.info, t.info);
  write_text(f.melanin_ratio, t.melanin_ratio);
}

// The rock dove's stack (configs/species/rockdove.yaml, variant forest): cortex 595 nm, air gap
// 500 nm, granules of melanin in air 2310 nm, lower cortex 595 nm.
const std::vector<double> kFlatThicknessNm = {595.0, 500.0, 2310.0, 595.0};
constexpr int kFlatVertices = 41;  // 10 µm at 250 nm spacing

Material granules(double f) { return Material::mixture(Material::air(), Material::melanin(), f); }

FeatherLabImportOptions rockdove_options() {
  FeatherLabImportOptions o;
  o.layers = {Material::keratin(), Material::air(), granules(0.9), Material::keratin()};
  o.melanin_ratio_layer = 2;  // the third layer (the config's melanin_ratio_layer: 3)
  return o;
}

// A flat barbule 10 µm wide: the top at y = 0 and one curve under each layer; the melanin ratio
// rising from 0.8 to 1.0 along the interior vertices (or 0.9 everywhere); written left to right
// or, as the same section, right to left.
FeatherLabTexts flat_texts(bool constant_ratio = false, bool right_to_left = false) {
  std::vector<Polyline> curves(5);
  double depth = 0.0;
  for (std::size_t c = 0; c < curves.size(); ++c) {
    for (int k = 0; k < kFlatVertices; ++k) curves[c].push_back({-5000.0 + 250.0 * k, -depth});
    if (c < kFlatThicknessNm.size()) depth += kFlatThicknessNm[c];
  }
  std::vector<double> ratio;
  for (int k = 1; k + 1 < kFlatVertices; ++k) {
    ratio.push_back(constant_ratio ? 0.9 : 0.8 + 0.2 * (k - 1) / (kFlatVertices - 3));
  }
  if (right_to_left) {
    for (Polyline& c : curves) std::reverse(c.begin(), c.end());
    std::reverse(ratio.begin(), ratio.end());
  }
  return featherlab_texts(curves, ratio);
}

double expected_flat_fraction(int node) {
  const int k = std::min(std::max(node, 1), kFlatVertices - 2);  // the ends take their neighbour's value
  return 0.8 + 0.2 * (k - 1) / (kFlatVertices - 3);
}

}  // namespace

TEST_CASE("featherlab import: a flat four-layer barbule gives its stack at every node", "[featherlab-import]") {
  const bool right_to_left = GENERATE(false, true);
  INFO((right_to_left ? "written right to left" : "written left to right"));
  const CrossSection cs = parse_featherlab_instance(flat_texts(false, right_to_left), rockdove_options());
  CHECK(validate(cs).empty());
  REQUIRE(cs.top.size() == kFlatVertices);
  REQUIRE(cs.layered);
  CHECK(cs.layered->boundaries.size() == 4);
  // Regions: the keratin body, the air gap and the granular layer (the keratin layers are the body's).
  REQUIRE(cs.regions.size() == 3);
  CHECK(cs.regions[1].role == RegionRole::air_gap);
  CHECK(cs.regions[2].role == RegionRole::granular_layer);
  CHECK(cs.regions[2].material.fraction() == Approx(0.9).epsilon(1e-3));  // the mean of 0.8 .. 1.0 and two ends
  for (int node = 0; node < kFlatVertices; ++node) {
    INFO("node " << node);
    const LayerProfile p = layer_profile_at(cs, static_cast<std::size_t>(node));
    REQUIRE(p.layers.size() == 4);
    for (std::size_t k = 0; k < 4; ++k) CHECK(p.layers[k].thickness_nm == Approx(kFlatThicknessNm[k]).epsilon(1e-12));
    CHECK(p.layers[0].material.kind() == Material::Kind::keratin);
    CHECK(p.layers[1].material.kind() == Material::Kind::air);
    REQUIRE(p.layers[2].material.kind() == Material::Kind::mixture);
    CHECK(p.layers[2].material.host().kind() == Material::Kind::air);
    CHECK(p.layers[2].material.guest().kind() == Material::Kind::melanin);
    // Node 0 and node 40: the normal line passes through the boundary's end vertex (layer_profile_at
    // used to walk to the far end there and take the last segment's fraction).
    CHECK(p.layers[2].material.fraction() == Approx(expected_flat_fraction(node)).epsilon(1e-12));
    CHECK(p.layers[3].material.kind() == Material::Kind::keratin);
    CHECK(p.substrate.kind() == Material::Kind::air);
  }
}

namespace {

// A procedural instance in FeatherLab's layout: the top and every boundary as curves, the media
// between them as `layers`, and the melanin ratio per top vertex but the ends, read off the
// mixture boundary (its own values when it has the top's vertices, as the rock dove's offset
// curves do; else interpolated in x at the top's vertices, as FeatherLab's generators sample the
// ratio along the top for the starling's core).
struct Written {
  FeatherLabTexts texts;
  FeatherLabImportOptions options;
  bool resampled = false;  // the ratio was interpolated onto the top's vertices
};

Written as_featherlab(const CrossSection& cs) {
  const LayeredModel& m = *cs.layered;
  Written w;
  std::vector<Polyline> curves = {cs.top};
  w.options.layers = {m.below_top};
  for (std::size_t b = 0; b < m.boundaries.size(); ++b) {
    curves.push_back(m.boundaries[b].points);
    if (b + 1 < m.boundaries.size()) w.options.layers.push_back(m.boundaries[b].below);
    if (!m.boundaries[b].fraction.empty()) w.options.melanin_ratio_layer = b + 1;
  }
  REQUIRE(w.options.melanin_ratio_layer);
  const LayerBoundary& mix = m.boundaries[*w.options.melanin_ratio_layer - 1];
  std::vector<double> ratio;
  w.resampled = mix.points.size() != cs.top.size();
  for (std::size_t j = 1; j + 1 < cs.top.size(); ++j) {
    if (!w.resampled) {
      ratio.push_back(mix.fraction[j]);
      continue;
    }
    const double x = cs.top[j].x;
    std::size_t i = 1;
    while (i + 1 < mix.points.size() && mix.points[i].x < x) ++i;
    const double s = std::clamp((x - mix.points[i - 1].x) / (mix.points[i].x - mix.points[i - 1].x), 0.0, 1.0);
    ratio.push_back((1.0 - s) * mix.fraction[i - 1] + s * mix.fraction[i]);
  }
  w.texts = featherlab_texts(curves, ratio);
  return w;
}

// The imported section's layer profile at every top vertex against the procedural one: the same
// thicknesses (to the rounding of 17 digits in µm) and materials; the melanin fraction equal
// away from the two end vertices at each side (FeatherLab has no ratio at the ends), to within
// `fraction_tolerance`.
void check_same_profiles(const CrossSection& procedural, const CrossSection& imported, double fraction_tolerance) {
  REQUIRE(imported.top.size() == procedural.top.size());
  const std::size_t n = procedural.top.size();
  const std::vector<LayerProfile> a = layer_profiles(procedural), b = layer_profiles(imported);
  double worst_fraction = 0.0;
  for (std::size_t node = 0; node < n; ++node) {
    INFO("node " << node << " of " << n);
    REQUIRE(a[node].layers.size() == b[node].layers.size());
    for (std::size_t k = 0; k < a[node].layers.size(); ++k) {
      const Layer &la = a[node].layers[k], &lb = b[node].layers[k];
      CHECK(std::abs(la.thickness_nm - lb.thickness_nm) <= 1e-9 * (1.0 + la.thickness_nm));
      REQUIRE(la.material.kind() == lb.material.kind());
      if (la.material.kind() == Material::Kind::mixture) {
        CHECK(la.material.host().kind() == lb.material.host().kind());
        CHECK(la.material.guest().kind() == lb.material.guest().kind());
        if (node >= 2 && node + 2 < n) worst_fraction = std::max(worst_fraction, std::abs(la.material.fraction() - lb.material.fraction()));
      }
    }
  }
  WARN(procedural.label << ": largest melanin fraction difference " << worst_fraction);
  CHECK(worst_fraction <= fraction_tolerance);
}

}  // namespace

TEST_CASE("featherlab import: a procedural rock dove written as FeatherLab files gives its layer profile back",
          "[featherlab-import]") {
  const CrossSection procedural = testing::species("rockdove").structure->generate(0);
  REQUIRE(procedural.layered);
  REQUIRE(procedural.layered->boundaries.size() == 4);  // cortex | air gap | granules | lower cortex
  const Written w = as_featherlab(procedural);
  CHECK(*w.options.melanin_ratio_layer == 2);
  CHECK_FALSE(w.resampled);  // the granules' upper boundary is an offset of the top, vertex by vertex
  const CrossSection imported = parse_featherlab_instance(w.texts, w.options);
  CHECK(validate(imported).empty());
  check_same_profiles(procedural, imported, 1e-12);
}

TEST_CASE("featherlab import: procedural starling and bronzewing instances written as FeatherLab files give their "
          "layer profiles back", "[featherlab-import]") {
  // Types 2 and 3, FeatherLab's starling layout: the top, the two chains of each melanosome row
  // (1 row per side for the starling, 6 for the bronzewing), the bottom; keratin | melanin |
  // keratin | ... | keratin-melanin core | ... | melanin | keratin.
  const auto [name, rows_per_side] = GENERATE(std::make_pair(std::string("starling"), 1), std::make_pair(std::string("bronzewing"), 6));
  INFO(name);
  const CrossSection procedural = testing::species(name).structure->generate(0);
  REQUIRE(procedural.layered);
  REQUIRE(procedural.layered->boundaries.size() == static_cast<std::size_t>(4 * rows_per_side + 1));
  const Written w = as_featherlab(procedural);
  CHECK(*w.options.melanin_ratio_layer == static_cast<std::size_t>(2 * rows_per_side));
  CHECK(w.resampled);
  const CrossSection imported = parse_featherlab_instance(w.texts, w.options);
  CHECK(validate(imported).empty());
  // The core's fraction is resampled twice by linear interpolation, onto the top's vertices and
  // back onto the boundary's, each off by at most h²/8·|f''|: with h = 30 nm and a profile of
  // half-range 0.2 (the starling's; the bronzewing's 0.05) and correlation length 1 µm
  // (|f''| ≲ 0.2·(2π/1 µm)² = 7.9e-6 /nm²), 8.9e-4 each. A ratio shifted by one top vertex would be off by h·|f'| ≈ 0.04.
  check_same_profiles(procedural, imported, 2e-3);
}

TEST_CASE("featherlab import: featherlab_files reads file n + 1 for instance n", "[featherlab-import]") {
  const fs::path dir = scratch("generator");
  fs::create_directories(dir / "geometry");
  write_instance(dir / "geometry", 1, flat_texts());
  const std::string head = "species: featherlab-flat\nreflection: {model: multilayer}\nstructure:\n"
                           "  generator: featherlab_files\n  instances: geometry\n";
  const std::string layers = "  layers: [keratin, air, {mix: [air, melanin], fraction: 0.9}, keratin]\n";
  write_text(dir / "flat.yaml", head + layers + "  melanin_ratio_layer: 3\n");
  const SpeciesConfig s = load_species_config(dir / "flat.yaml", testing::registry());
  const CrossSection cs = s.structure->generate(0);
  CHECK(cs.generator == "featherlab_files");
  CHECK(cs.top.size() == kFlatVertices);
  CHECK(layer_profile_at(cs, 20).layers[2].thickness_nm == Approx(2310.0).epsilon(1e-12));
  // Instance 1 would be file 2, which is not there.
  CHECK_THROWS_AS(s.structure->generate(1), InputFileError);

  // A folder per instance: {index} in `instances`, the file number n + first_number in each.
  for (int n : {0, 3}) {
    fs::create_directories(dir / ("inst-" + std::to_string(n)));
    write_instance(dir / ("inst-" + std::to_string(n)), n, flat_texts());
  }
  write_text(dir / "per-folder.yaml", "species: featherlab-flat\nreflection: {model: multilayer}\nstructure:\n"
                                      "  generator: featherlab_files\n  instances: \"inst-{index}\"\n  first_number: 0\n" +
                                          layers);
  const SpeciesConfig per_folder = load_species_config(dir / "per-folder.yaml", testing::registry());
  CHECK(per_folder.structure->generate(3).instance == 3);
  CHECK_THROWS_AS(per_folder.structure->generate(1), InputFileError);  // no inst-1

  auto refused = [&](const std::string& yaml, const std::string& expected) {
    write_text(dir / "bad.yaml", yaml);
    try {
      (void)load_species_config(dir / "bad.yaml", testing::registry());
      FAIL("no error for " << expected);
    } catch (const ConfigError& e) {
      CHECK_THAT(e.what(), Catch::Contains(expected));
    }
  };
  refused(head + "  layers: [keratin, air, melanin, keratin]\n  melanin_ratio_layer: 3\n", "melanin_ratio_layer");
  refused(head + layers + "  melanin_ratio_layer: 7\n", "melanin_ratio_layer");
  refused("species: x\nreflection: {model: multilayer}\nstructure:\n  generator: featherlab_files\n"
          "  instances: nowhere\n" + layers, "instances");
}

TEST_CASE("featherlab import: the flat barbule's far field is validation_shape slab's", "[featherlab-import]") {
  const fs::path dir = scratch("slab");
  fs::create_directories(dir / "geometry");
  write_instance(dir / "geometry", 1, flat_texts(true));
  write_text(dir / "featherlab.yaml",
             "species: featherlab-flat\nreflection: {model: multilayer}\nstructure:\n  generator: featherlab_files\n"
             "  instances: geometry\n  layers: [keratin, air, {mix: [air, melanin], fraction: 0.9}, keratin]\n"
             "  melanin_ratio_layer: 3\n");
  write_text(dir / "slab.yaml",
             "species: slab-flat\nreflection: {model: multilayer}\n"
             "structure:\n  generator: validation_shape\n  shape: slab\n  width_um: 10\n  spacing_nm: 250\n"
             "  stack:\n    layers:\n      - {material: keratin, thickness_nm: 595}\n"
             "      - {material: air, thickness_nm: 500}\n"
             "      - {material: {mix: [air, melanin], fraction: 0.9}, thickness_nm: 2310}\n"
             "      - {material: keratin, thickness_nm: 595}\n    substrate: air\n");
  const SpeciesConfig imported = load_species_config(dir / "featherlab.yaml", testing::registry());
  const SpeciesConfig slab = load_species_config(dir / "slab.yaml", testing::registry());
  REQUIRE(slab.structure->generate(0).top.size() == imported.structure->generate(0).top.size());
  SimulationRequest request;
  request.lambdas_nm = {450.0, 600.0};
  request.theta_deg = {20.0};
  request.instances = 1;
  const FarFieldSet a = simulate(imported, request), b = simulate(slab, request);
  REQUIRE(a.units.size() == 2);
  REQUIRE(b.units.size() == 2);
  for (std::size_t u = 0; u < a.units.size(); ++u) {
    const FarField &fa = a.units[u].instances.at(0), &fb = b.units[u].instances.at(0);
    double worst = 0.0, scale = 0.0;
    for (int pol = 0; pol < 2; ++pol) {
      REQUIRE(fa.field[pol].size() == fb.field[pol].size());
      for (std::size_t d = 0; d < fa.field[pol].size(); ++d) {
        for (int c = 0; c < 3; ++c) {
          scale = std::max(scale, std::abs(fb.field[pol][d][c]));
          worst = std::max(worst, std::abs(fa.field[pol][d][c] - fb.field[pol][d][c]));
        }
      }
    }
    REQUIRE(scale > 0.0);
    WARN("featherlab flat barbule against validation_shape slab, unit " << u << ": relative difference " << worst / scale);
    CHECK(worst / scale <= 1e-12);
  }
}

namespace {

void check_refused(FeatherLabTexts t, const std::string& file, const std::string& expected,
                   const FeatherLabImportOptions& o = rockdove_options()) {
  try {
    (void)parse_featherlab_instance(t, o);
    FAIL("no error for " << expected);
  } catch (const InputFileError& e) {
    CHECK(e.file() == file);
    CHECK_THAT(e.what(), Catch::Contains(expected));
  }
}

std::string replace_line(const std::string& text, int line, const std::string& with) {
  std::istringstream in(text);
  std::string out, l;
  for (int k = 1; std::getline(in, l); ++k) out += (k == line ? with : l) + "\n";
  return out;
}

}  // namespace

TEST_CASE("featherlab import: bad files are refused naming the file, the line and the field", "[featherlab-import]") {
  const FeatherLabTexts good = flat_texts();
  FeatherLabTexts t = good;
  t.xyvals = replace_line(good.xyvals, 3, "-4.5,nan");
  check_refused(t, "xyvals1.txt", "xyvals1.txt: line 3: y: nan is not a finite number");
  t.xyvals = replace_line(good.xyvals, 4, "-4.25,1e999");
  check_refused(t, "xyvals1.txt", "line 4: y: 1e999 is not a finite number");
  t.xyvals = replace_line(good.xyvals, 5, "-4,0,7");
  check_refused(t, "xyvals1.txt", "line 5: 3 fields, expected 2 (x,y)");
  t.xyvals = replace_line(good.xyvals, 6, "abc,0");
  check_refused(t, "xyvals1.txt", "line 6: x: 'abc' is not a number");
  // x going backwards within the top.
  t.xyvals = replace_line(good.xyvals, 10, "-6,0");
  check_refused(t, "xyvals1.txt", "line 10: x: curve 1, the top surface, is not monotone");

  t = good;
  t.info = replace_line(good.info, 5, "164,40");  // one vertex short of the rows
  check_refused(t, "info1.txt", "line 5: the curves cover 204 rows of xyvals1.txt, which has 205");
  t.info = replace_line(good.info, 2, "42,41");  // a gap after curve 1
  check_refused(t, "info1.txt", "line 2: start: 42, but curve 2 must start at row 41");
  t.info = replace_line(good.info, 5, "164,42");  // past the last row
  check_refused(t, "info1.txt", "line 5: count: curve 5 ends at row 206");
  t.info = replace_line(good.info, 1, "0,4.5");
  check_refused(t, "info1.txt", "line 1: count: '4.5' is not a whole number");
  t.info = "0,205\n";
  check_refused(t, "info1.txt", "1 curve");

  // A closed curve (a melanosome outline): the non-layered types are not read.
  t = good;
  t.xyvals = replace_line(good.xyvals, 82, "-5,-0.595");
  check_refused(t, "xyvals1.txt", "line 82: curve 2 is closed");

  // The wrong number of melanin ratios for the top's 41 vertices.
  t = good;
  t.melanin_ratio = replace_line(good.melanin_ratio, 39, "");
  check_refused(t, "melaninRatio1.txt", "38 values, but the top surface has 41 vertices");
  t.melanin_ratio = replace_line(good.melanin_ratio, 7, "1.5");
  check_refused(t, "melaninRatio1.txt", "line 7: melanin ratio: 1.500000 is outside [0, 1]");

  // Layers in the config that do not match the curves.
  FeatherLabImportOptions three = rockdove_options();
  three.layers.pop_back();
  check_refused(good, "info1.txt", "5 curves, so 4 layers between them, but `layers` gives 3 materials", three);

  // The air gap's upper curve bulging through the top surface: crossing curves, as validate() says.
  t = good;
  t.xyvals = replace_line(good.xyvals, 41 + 21, "0,0.2");
  check_refused(t, "xyvals1.txt", "the curves do not make a valid cross section");
}

// The fuzz harness's seeds (fuzz/corpus/featherlab: the three files, each ended by a line "%%")
// are valid instances, so that fuzzing starts from sections that reach every check.
TEST_CASE("featherlab import: the fuzz seeds are valid instances", "[featherlab-import]") {
  const fs::path corpus = fs::path(PLUMAGE_SOURCE_DIR) / "fuzz" / "corpus" / "featherlab";
  int seeds = 0;
  for (const auto& entry : fs::directory_iterator(corpus)) {
    INFO(entry.path());
    const std::string text = read_input_file(entry.path(), "fuzz seed");
    const std::size_t a = text.find("\n%%\n"), b = text.find("\n%%\n", a + 4);
    REQUIRE(b != std::string::npos);
    FeatherLabTexts t;
    t.xyvals = text.substr(0, a + 1);
    t.info = text.substr(a + 4, b + 1 - (a + 4));
    t.melanin_ratio = text.substr(b + 4);
    t.xyvals_name = "xyvals1.txt";
    t.info_name = "info1.txt";
    t.melanin_ratio_name = "melaninRatio1.txt";
    const CrossSection cs = parse_featherlab_instance(t, rockdove_options());
    CHECK(cs.layered->boundaries.size() == 4);
    seeds += 1;
  }
  CHECK(seeds == 2);
}
