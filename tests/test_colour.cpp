// Colour science: CIE tables, spectrum → XYZ on any grid, XYZ → sRGB, transfer function, gamut.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <thread>
#include <vector>

#include "plumage/colour.hpp"
#include "plumage/error.hpp"

using namespace plumage;
namespace fs = std::filesystem;

namespace {

std::vector<double> grid(double from, double step, double to) {
  std::vector<double> g;
  for (int i = 0; from + i * step <= to + 1e-9; ++i) g.push_back(from + i * step);
  return g;
}

// A smooth, strongly coloured reflectance (a bump in the green plus a rising red tail).
double smooth_reflectance(double l) {
  return 0.1 + 0.6 * std::exp(-0.5 * std::pow((l - 530.0) / 35.0, 2)) +
         0.3 / (1.0 + std::exp(-(l - 640.0) / 15.0));
}

std::vector<double> sample(const std::vector<double>& g, double (*f)(double)) {
  std::vector<double> s;
  for (double l : g) s.push_back(f(l));
  return s;
}

fs::path fresh_folder(const std::string& name) {
  static int counter = 0;
  const fs::path p = fs::temp_directory_path() /
                     ("plumage-colour-" + name + "-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

}  // namespace

TEST_CASE("the shipped CIE tables load once and are sane", "[colour]") {
  const CieTables& t = cie_tables();
  REQUIRE(t.lambda_nm.size() == 81);
  CHECK(t.lambda_nm.front() == 380.0);
  CHECK(t.lambda_nm.back() == 780.0);
  // CIE 15:2004 landmarks: ȳ(555) = 1, D65(560) = 100.
  CHECK(t.ybar[(555 - 380) / 5] == Approx(1.0).margin(1e-6));
  CHECK(t.d65[(560 - 380) / 5] == Approx(100.0).margin(1e-6));

  // Concurrent first use sees one table.
  std::vector<const CieTables*> seen(4);
  std::vector<std::thread> threads;
  for (int i = 0; i < 4; ++i) threads.emplace_back([&seen, i] { seen[static_cast<std::size_t>(i)] = &cie_tables(); });
  for (auto& th : threads) th.join();
  for (auto* p : seen) CHECK(p == &t);
}

TEST_CASE("malformed CIE tables are errors naming file and line", "[colour]") {
  const fs::path dir = fresh_folder("tables");
  const fs::path data = fs::path(PLUMAGE_SOURCE_DIR) / "data";
  fs::copy_file(data / "cie_d65_5nm.csv", dir / "cie_d65_5nm.csv");
  CHECK_THROWS_WITH(load_cie_tables(dir), Catch::Contains("cie1931_2deg_5nm.csv: cannot open"));

  std::ofstream(dir / "cie1931_2deg_5nm.csv") << "# comment\nlambda_nm,xbar,ybar,zbar\n380,0.1,0.2,0.3\n385,0.1,zz,0.3\n";
  CHECK_THROWS_WITH(load_cie_tables(dir), Catch::Contains("cie1931_2deg_5nm.csv:4: 'zz' is not a number"));
  std::ofstream(dir / "cie1931_2deg_5nm.csv") << "lambda_nm,xbar,ybar,zbar\n380,0.1,0.2,0.3\n385,0.1,0.3\n";
  CHECK_THROWS_WITH(load_cie_tables(dir), Catch::Contains("cie1931_2deg_5nm.csv:3: expected 4 numbers, found 3"));
  std::ofstream(dir / "cie1931_2deg_5nm.csv") << "lambda_nm,xbar,ybar,zbar\n385,0.1,0.2,0.3\n380,0.1,0.2,0.3\n";
  CHECK_THROWS_WITH(load_cie_tables(dir), Catch::Contains("cie1931_2deg_5nm.csv:3: wavelengths must increase"));
  std::ofstream(dir / "cie1931_2deg_5nm.csv") << "lambda_nm,xbar,ybar,zbar\n380,0.1,0.2,0.3\n385,0.1,0.2,0.3\n";
  CHECK_THROWS_WITH(load_cie_tables(dir), Catch::Contains("81 wavelengths"));
  fs::remove_all(dir);
}

TEST_CASE("a perfect white reflector under D65 is the D65 white point and sRGB white", "[colour]") {
  // Independent trapezoid integrals straight from the tables.
  const CieTables& t = cie_tables();
  double sx = 0, sy = 0, sz = 0;
  for (std::size_t j = 0; j + 1 < t.lambda_nm.size(); ++j) {
    const double h = 0.5 * (t.lambda_nm[j + 1] - t.lambda_nm[j]);
    sx += h * (t.xbar[j] * t.d65[j] + t.xbar[j + 1] * t.d65[j + 1]);
    sy += h * (t.ybar[j] * t.d65[j] + t.ybar[j + 1] * t.d65[j + 1]);
    sz += h * (t.zbar[j] * t.d65[j] + t.zbar[j + 1] * t.d65[j + 1]);
  }
  const Xyz w = d65_white_point();
  CHECK(w.x == Approx(sx / sy).margin(1e-12));
  CHECK(w.y == Approx(1.0).margin(1e-12));
  CHECK(w.z == Approx(sz / sy).margin(1e-12));
  // Published CIE 15:2004 values.
  CHECK(w.x == Approx(0.95047).margin(2e-3));
  CHECK(w.z == Approx(1.08883).margin(2e-3));
  const Chromaticity c = chromaticity(w);
  CHECK(c.x == Approx(0.3127).margin(1e-4));
  CHECK(c.y == Approx(0.3290).margin(1e-4));

  // A constant spectrum is the same white on any grid (end values held beyond the grid).
  for (const auto& g : {grid(400, 6, 694), grid(400, 1, 700), grid(380, 5, 780), grid(300, 7, 900)}) {
    const Xyz x = spectrum_to_xyz(g, std::vector<double>(g.size(), 1.0));
    CHECK(x.x == Approx(w.x).margin(1e-12));
    CHECK(x.y == Approx(w.y).margin(1e-12));
    CHECK(x.z == Approx(w.z).margin(1e-12));
  }

  const Rgb rgb = xyz_to_linear_srgb(w);
  CHECK(rgb.r == Approx(1.0).margin(2e-3));
  CHECK(rgb.g == Approx(1.0).margin(2e-3));
  CHECK(rgb.b == Approx(1.0).margin(2e-3));
  CHECK(to_srgb8(w) == Rgb8{255, 255, 255});
  const Rgb half = xyz_to_linear_srgb(Xyz{0.18 * w.x, 0.18 * w.y, 0.18 * w.z});
  CHECK(half.r == Approx(half.g).margin(5e-4));
  CHECK(half.b == Approx(half.g).margin(5e-4));
}

TEST_CASE("D65 as an emitted spectrum gives the white reflector's XYZ", "[colour]") {
  const CieTables& t = cie_tables();
  const Xyz e = radiance_to_xyz(t.lambda_nm, t.d65);
  const Xyz w = d65_white_point();
  CHECK(e.x == Approx(w.x).margin(1e-12));
  CHECK(e.y == Approx(w.y).margin(1e-12));
  CHECK(e.z == Approx(w.z).margin(1e-12));
}

TEST_CASE("a narrow band at 550 nm lies on the spectral locus", "[colour]") {
  const CieTables& t = cie_tables();
  const std::size_t j = (550 - 380) / 5;
  const double sum = t.xbar[j] + t.ybar[j] + t.zbar[j];
  // 0.2 nm wide (plus 0.1 nm ramps): narrow enough that the kinks of the 5 nm tables at
  // 550 nm shift the chromaticity by only ~1e-5.
  const std::vector<double> g{380, 549.8, 549.9, 550.1, 550.2, 780};
  const std::vector<double> box{0, 0, 1, 1, 0, 0};
  const Chromaticity c = chromaticity(spectrum_to_xyz(g, box));
  CHECK(c.x == Approx(t.xbar[j] / sum).margin(1e-4));
  CHECK(c.y == Approx(t.ybar[j] / sum).margin(1e-4));
  // CIE 15:2004 spectral locus at 550 nm.
  CHECK(c.x == Approx(0.3016).margin(1e-3));
  CHECK(c.y == Approx(0.6923).margin(1e-3));
  // A pure spectral colour is far outside sRGB: red goes negative.
  CHECK(xyz_to_linear_srgb(spectrum_to_xyz(g, box)).r < 0.0);
}

TEST_CASE("XYZ of a smooth spectrum does not depend on its grid", "[colour]") {
  const auto coarse = grid(400, 6, 694);
  const auto fine = grid(400, 1, 700);
  const auto finest = grid(380, 0.25, 780);
  const Xyz a = SpectralToXyz(coarse).apply(sample(coarse, smooth_reflectance));
  const Xyz b = SpectralToXyz(fine).apply(sample(fine, smooth_reflectance));
  const Xyz c = SpectralToXyz(finest).apply(sample(finest, smooth_reflectance));
  CHECK(a.x == Approx(b.x).margin(1e-3));
  CHECK(a.y == Approx(b.y).margin(1e-3));
  CHECK(a.z == Approx(b.z).margin(1e-3));
  CHECK(b.x == Approx(c.x).margin(1e-3));
  CHECK(b.y == Approx(c.y).margin(1e-3));
  CHECK(b.z == Approx(c.z).margin(1e-3));
  // One-off and precomputed paths agree.
  const Xyz d = spectrum_to_xyz(coarse, sample(coarse, smooth_reflectance));
  CHECK(d.x == a.x);
  CHECK(d.y == a.y);
  CHECK(d.z == a.z);
}

TEST_CASE("reference-style bins integrate the observer over each bin", "[colour]") {
  // bins(400, 6, 50) of a constant equals the exact integral over [400, 700] with nothing
  // outside, which the pointwise path gives for a 1 nm grid on [400, 700] with zero extension.
  const SpectralToXyz bins = SpectralToXyz::bins(400, 6, 50);
  const auto g = grid(400, 1, 700);
  const SpectralToXyz inside(g, SpectrumKind::reflectance, Extension::zero);
  const Xyz a = bins.apply(std::vector<double>(50, 1.0));
  const Xyz b = inside.apply(std::vector<double>(g.size(), 1.0));
  CHECK(a.x == Approx(b.x).margin(1e-12));
  CHECK(a.y == Approx(b.y).margin(1e-12));
  CHECK(a.z == Approx(b.z).margin(1e-12));
  CHECK(a.y < 1.0);
  CHECK(a.y > 0.99);
}

TEST_CASE("bad grids and spectra are rejected", "[colour]") {
  const std::vector<double> repeated{400, 500, 500};
  CHECK_THROWS_WITH(SpectralToXyz(repeated), Catch::Contains("increase strictly"));
  CHECK_THROWS_AS(SpectralToXyz(std::vector<double>{}), Error);
  const SpectralToXyz s(grid(400, 6, 694));
  CHECK_THROWS_WITH(s.apply(std::vector<double>(49, 1.0)), Catch::Contains("49 samples, the wavelength grid 50"));
  CHECK_THROWS_AS(SpectralToXyz::bins(400, 0, 50), Error);
}

TEST_CASE("the sRGB matrices are IEC 61966-2-1's", "[colour]") {
  const Rgb w = xyz_to_linear_srgb(Xyz{0.3127 / 0.3290, 1.0, (1 - 0.3127 - 0.3290) / 0.3290});
  CHECK(w.r == Approx(1.0).margin(1e-9));
  CHECK(w.g == Approx(1.0).margin(1e-9));
  CHECK(w.b == Approx(1.0).margin(1e-9));
  // The standard's rounded XYZ → RGB rows.
  const Rgb r = xyz_to_linear_srgb({1, 0, 0}), g = xyz_to_linear_srgb({0, 1, 0}), b = xyz_to_linear_srgb({0, 0, 1});
  CHECK(r.r == Approx(3.2406).margin(6e-4));
  CHECK(g.r == Approx(-1.5372).margin(6e-4));
  CHECK(b.r == Approx(-0.4986).margin(6e-4));
  CHECK(r.g == Approx(-0.9689).margin(6e-4));
  CHECK(g.g == Approx(1.8758).margin(6e-4));
  CHECK(b.g == Approx(0.0415).margin(6e-4));
  CHECK(r.b == Approx(0.0557).margin(6e-4));
  CHECK(g.b == Approx(-0.2040).margin(6e-4));
  CHECK(b.b == Approx(1.0570).margin(6e-4));
  CHECK(srgb_luminance({1, 0, 0}) == Approx(0.2126).margin(1e-4));
  CHECK(srgb_luminance({0, 1, 0}) == Approx(0.7152).margin(1e-4));
  CHECK(srgb_luminance({0, 0, 1}) == Approx(0.0722).margin(1e-4));
  // The two directions are inverse.
  const Rgb c{0.2, 0.7, 0.4};
  const Rgb back = xyz_to_linear_srgb(linear_srgb_to_xyz(c));
  CHECK(back.r == Approx(c.r).margin(1e-9));
  CHECK(back.g == Approx(c.g).margin(1e-9));
  CHECK(back.b == Approx(c.b).margin(1e-9));
}

TEST_CASE("the sRGB transfer function: breakpoints and round trip", "[colour]") {
  CHECK(srgb_encode(0.0031308) == Approx(0.04045).margin(1e-6));
  CHECK(srgb_decode(0.04045) == Approx(0.0031308).margin(1e-6));
  // Both pieces meet at the breakpoint (the standard's constants make a gap of ~1e-8).
  CHECK(1.055 * std::pow(0.0031308, 1 / 2.4) - 0.055 == Approx(12.92 * 0.0031308).margin(1e-6));
  CHECK(srgb_encode(0.0) == 0.0);
  CHECK(srgb_encode(1.0) == Approx(1.0).margin(1e-12));
  CHECK(srgb_encode(0.001) == Approx(0.01292).margin(1e-12));
  CHECK(srgb_encode(0.18) == Approx(0.4613561).margin(1e-6));
  for (int i = 0; i <= 1000; ++i) {
    const double v = i / 1000.0;
    CHECK(srgb_decode(srgb_encode(v)) == Approx(v).margin(1e-12));
    CHECK(srgb_encode(srgb_decode(v)) == Approx(v).margin(1e-12));
  }
  CHECK(to_srgb8(Rgb{0.5, 0.18, 0.0}) == Rgb8{188, 118, 0});
  // Every 8-bit code decodes and re-encodes to itself.
  for (int code = 0; code < 256; ++code) {
    const double l = srgb_decode(code / 255.0);
    CHECK(to_srgb8(Rgb{l, l, l}).g == code);
  }
}

TEST_CASE("out-of-gamut colours: clip or desaturate at constant luminance", "[colour]") {
  const Rgb in{0.2, 0.5, 0.7};
  for (auto m : {GamutMapping::clip, GamutMapping::desaturate}) {
    const Rgb o = map_to_gamut(in, m);
    CHECK(o.r == in.r);
    CHECK(o.g == in.g);
    CHECK(o.b == in.b);
  }
  const Rgb out{-0.15, 0.6, 1.3};
  const Rgb c = map_to_gamut(out, GamutMapping::clip);
  CHECK(c.r == 0.0);
  CHECK(c.g == 0.6);
  CHECK(c.b == 1.0);

  const Rgb d = map_to_gamut(out, GamutMapping::desaturate);
  for (double v : {d.r, d.g, d.b}) {
    CHECK(v >= 0.0);
    CHECK(v <= 1.0);
  }
  CHECK(srgb_luminance(d) == Approx(srgb_luminance(out)).margin(1e-12));
  // On the line from the grey of that luminance through the original colour.
  const double y = srgb_luminance(out);
  const double t = (d.g - y) / (out.g - y);
  CHECK(d.r - y == Approx(t * (out.r - y)).margin(1e-12));
  CHECK(d.b - y == Approx(t * (out.b - y)).margin(1e-12));
  // Just enough to fit: some channel sits on the gamut boundary.
  CHECK((std::min({d.r, d.g, d.b}) < 1e-12 || std::max({d.r, d.g, d.b}) > 1 - 1e-12));

  // Brighter than white becomes white; NaN becomes black.
  const Rgb bright = map_to_gamut({2.0, 1.5, 3.0}, GamutMapping::desaturate);
  CHECK(bright.r == 1.0);
  CHECK(bright.b == 1.0);
  CHECK(to_srgb8(Rgb{std::nan(""), 0.0, 0.0}) == Rgb8{0, 0, 0});
  const Rgb inf = map_to_gamut({INFINITY, 0.0, 0.0}, GamutMapping::desaturate);
  CHECK(std::isfinite(inf.r));
}
