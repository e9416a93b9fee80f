// `plumage brdf plot` and `brdf check` end to end (core/cli/cmd_brdf.cpp): a small synthetic material is
// written through the material IO, plotted for three incident directions with instances; bad
// input exits 2 (nothing written), a corrupt material fails with an error naming the file.
#include <catch2/catch.hpp>

#include "cli_run.hpp"

#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>

#include "bsdf_fixtures.hpp"
#include "plumage/feather_material.hpp"
#include "plumage/image.hpp"

namespace fs = std::filesystem;
using plumage::cli_test::Result;
using plumage::cli_test::run;
using plumage::cli_test::run_command;
using namespace plumage;
using namespace plumage::testing;

namespace {

fs::path scratch() { return plumage::cli_test::scratch_dir("plumage-test-brdf-cli"); }

// 10 bins over 400–700 nm whose reflectance peaks at 520 nm (a green feather), grid 4.
fs::path synthetic_material() {
  MaterialRecipe r;
  r.bins = 10;
  r.grid = 4;
  r.l0 = 0.2;
  r.m_eff = [](int, double, double) { return 0.15; };
  r.albedo = [](int w, double, double) { const double d = (400.0 + 30.0 * w - 520.0) / 60.0; return 0.1 + 0.6 * std::exp(-d * d); };
  FeatherMaterial m = make_material(r, [](const Lobe& l, double t) { return lobe_integral(l, t, 12, 3); });
  m.label = "synthetic/green";
  m.fidelity = "test";
  m.bin_width_nm = 30.0;
  for (int w = 0; w < r.bins; ++w) m.lambda_nm[static_cast<std::size_t>(w)] = 400.0 + 30.0 * w;
  m.noise = ar1_pool(16, 128, 0.9, 42);
  const fs::path file = scratch() / "green.plm";
  write_feather_material(file, m);
  return file;
}

}  // namespace

TEST_CASE("brdf plot: hemisphere pictures of the mean and instances", "[cli][brdf]") {
  const fs::path plm = synthetic_material();
  const fs::path png = scratch() / "fig.png";
  fs::remove(png);
  const Result r = run("brdf plot " + plm.string() + " --incident \"0,0 0,-45 45,0\" --instances 2 --size 48 --out " +
                       png.string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK(r.output.find("exposure") != std::string::npos);
  REQUIRE(fs::exists(png));
  CHECK_FALSE(fs::exists(fs::path(png).concat(".panels.tmp")));  // the panel folder is cleaned up
  const Image img = read_png(png);
  CHECK(img.width() > 300);
  CHECK(img.height() > 300);
  // A coloured picture: many distinct colours, some clearly green-dominated (the material
  // reflects most at 520 nm).
  std::set<int> colours;
  int green = 0;
  for (const Rgb8& p : img.pixels()) {
    colours.insert(p.r << 16 | p.g << 8 | p.b);
    green += p.g > 60 && p.g > p.r + 20 && p.g > p.b + 20;
  }
  CHECK(colours.size() > 200);
  CHECK(green > 100);
}

TEST_CASE("brdf check: white furnace at every table entry of a material", "[cli][brdf]") {
  const fs::path plm = synthetic_material();
  const Result r = run("brdf check " + plm.string() + " --transmission 0.05");
  INFO(r.output);
  CHECK(r.status == 0);
  CHECK(r.output.find("worst A_r + T over 320 table entries and cell centres") != std::string::npos);
  CHECK(run("brdf check " + plm.string() + " --transmission 2").status == 2);
}

TEST_CASE("brdf plot: bad input exits 2 and writes nothing; a corrupt material names the file", "[cli][brdf]") {
  const fs::path plm = synthetic_material();
  const fs::path png = scratch() / "bad.png";
  fs::remove(png);
  Result r = run("brdf plot " + plm.string() + " --incident \"0,95\" --out " + png.string());
  CHECK(r.status == 2);
  CHECK(r.output.find("--incident") != std::string::npos);
  r = run("brdf plot " + plm.string() + " --incident \"abc\" --out " + png.string());
  CHECK(r.status == 2);
  r = run("brdf plot " + (scratch() / "missing.plm").string() + " --out " + png.string());
  CHECK(r.status == 2);
  CHECK_FALSE(fs::exists(png));
  const fs::path corrupt = scratch() / "corrupt.plm";
  fs::copy_file(plm, corrupt, fs::copy_options::overwrite_existing);
  {
    std::fstream f(corrupt, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(200);
    f.put('\x5a');
  }
  r = run("brdf plot " + corrupt.string() + " --out " + png.string());
  CHECK(r.status != 0);
  CHECK(r.output.find("corrupt.plm") != std::string::npos);
  CHECK_FALSE(fs::exists(png));
}
