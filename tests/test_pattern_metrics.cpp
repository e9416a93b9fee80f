// The pattern metrics every solver comparison reports (pattern_metrics.hpp): each against what it
// must give on patterns whose answer is known.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "plumage/conventions.hpp"
#include "plumage/pattern_metrics.hpp"

using namespace plumage;

TEST_CASE("pattern_correlation: 1 for an affine copy, -1 for a mirrored one, NaN for a constant", "[metrics]") {
  const std::vector<double> a{0.1, 0.5, 2.0, 0.3, 0.0};
  std::vector<double> b, c;
  for (double x : a) b.push_back(3.0 * x + 1.0), c.push_back(-2.0 * x + 4.0);
  CHECK(pattern_correlation(a, b) == Approx(1.0).epsilon(1e-14));
  CHECK(pattern_correlation(a, c) == Approx(-1.0).epsilon(1e-14));
  CHECK(pattern_correlation(a, a) == 1.0);
  CHECK(std::isnan(pattern_correlation(a, std::vector<double>(a.size(), 2.0))));
  const std::vector<double> d{0.3, 0.1, 0.0, 2.0, 0.5};
  const double r = pattern_correlation(a, d);
  CHECK(r < 0.9);
  CHECK(r > -1.0);
  CHECK_THROWS(pattern_correlation(a, std::vector<double>(3, 1.0)));
}

TEST_CASE("relative_l2, reflected_fraction and compare_patterns", "[metrics]") {
  const std::vector<double> ref{1.0, 2.0, 2.0};  // ‖ref‖ = 3
  const std::vector<double> a{1.0, 2.0, 5.0};    // ‖a − ref‖ = 3
  CHECK(relative_l2(a, ref) == Approx(1.0).epsilon(1e-15));
  CHECK(relative_l2(ref, ref) == 0.0);
  CHECK(std::isnan(relative_l2(a, std::vector<double>(3, 0.0))));
  // A uniform density 1/π over n bins of π/n reflects everything.
  const int n = 90;
  CHECK(reflected_fraction(std::vector<double>(n, 1.0 / kPi), kPi / n) == Approx(1.0).epsilon(1e-14));
  const PatternComparison m = compare_patterns(a, ref, 0.5);
  CHECK(m.rel_l2 == relative_l2(a, ref));
  CHECK(m.correlation == pattern_correlation(a, ref));
  CHECK(m.total == Approx(4.0));
  CHECK(m.total_ref == Approx(2.5));
}

TEST_CASE("polarised_density: pol 0, 1 and their mean", "[metrics]") {
  FarField f;
  f.lambda_nm = 550.0;
  f.phi_o_rad = {-0.5, 0.0, 0.5};
  f.incident_power = {2.0, 4.0};
  for (int p = 0; p < 2; ++p) {
    f.field[p].resize(3);
    for (std::size_t j = 0; j < 3; ++j) f.field[p][j] = {Complex(1.0 + j + p, 0.0), Complex(0.0, 0.5), Complex(0.0, 0.0)};
  }
  const auto u0 = polarised_density(f, 0), u1 = polarised_density(f, 1), mean = polarised_density(f, 2);
  REQUIRE(u0.size() == 3);
  for (std::size_t j = 0; j < 3; ++j) {
    CHECK(u0[j] == f.reflectance_density(0, j));
    CHECK(u1[j] == f.reflectance_density(1, j));
    CHECK(mean[j] == 0.5 * (u0[j] + u1[j]));
    CHECK(u0[j] != u1[j]);
  }
  CHECK(mean == unpolarised_density(f));
  CHECK_THROWS(polarised_density(f, 3));
}
