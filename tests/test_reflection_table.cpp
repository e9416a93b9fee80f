// ReflectionTable: interpolation, grazing/back-facing/mirror rules, and the PLMRTAB file format.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "plumage/reflection_table.hpp"

using namespace plumage;

namespace {

// A smooth synthetic entry: cubic-friendly polynomials in (cos θ, cos φ), linear in λ.
JonesReflection synthetic(double lambda, double ct, double cp) {
  const double a = 0.3 + 0.2 * ct * ct - 0.1 * cp + 0.05 * ct * cp * cp + 1e-4 * lambda;
  return {{a, 0.1 * cp}, {0.02 * ct, -0.01}, {-0.03 * cp, 0.01 * ct}, {-a, 0.2 * ct * cp}};
}

ReflectionTable synthetic_table() {
  TableGrid g = TableGrid::uniform(400, 700, 4, 10, 12);
  ReflectionTable t(g, {"test-crystal", 190.0, "0123456789abcdef", 10.0, "unit test", ""});
  for (std::size_t l = 0; l < g.lambda_nm.size(); ++l)
    for (std::size_t i = 0; i < g.cos_theta.size(); ++i)
      for (std::size_t j = 0; j < g.cos_phi.size(); ++j)
        t.at(l, i, j) = synthetic(g.lambda_nm[l], g.cos_theta[i], g.cos_phi[j]);
  return t;
}

double diff(const JonesReflection& a, const JonesReflection& b) {
  return std::max({std::abs(a.ss - b.ss), std::abs(a.sp - b.sp), std::abs(a.ps - b.ps),
                   std::abs(a.pp - b.pp)});
}

}  // namespace

TEST_CASE("reflection table interpolates smoothly between nodes", "[table]") {
  const ReflectionTable t = synthetic_table();
  // Exact at the nodes.
  const auto& g = t.grid();
  CHECK(diff(t.query(g.lambda_nm[1], std::acos(g.cos_theta[4]), std::acos(g.cos_phi[7])),
             t.at(1, 4, 7)) < 1e-12);
  // Between nodes (interior cells): a quadratic in cos is reproduced to the cubic Hermite's
  // accuracy; linear in λ exactly.
  double worst = 0;
  for (double ct : {0.23, 0.47, 0.66, 0.88})
    for (double cp : {0.21, 0.43, 0.72, 0.91})
      worst = std::max(worst, diff(t.query(512.0, std::acos(ct), std::acos(cp)), synthetic(512.0, ct, cp)));
  INFO("worst interior error " << worst);
  CHECK(worst < 2e-4);
}

TEST_CASE("reflection table grazing, back-facing and mirror rules", "[table]") {
  const ReflectionTable t = synthetic_table();
  const JonesReflection g = grazing_jones();
  CHECK(diff(t.query(550, 0.2, kPi / 2), g) < 1e-12);
  CHECK(diff(t.query(550, kPi / 2, 0.3), g) < 1e-12);
  CHECK(diff(t.query(550, 0.2, 2.0), JonesReflection{}) == 0.0);  // back-facing
  // Below the first cos φ node the value blends continuously into the grazing limit.
  const double near = std::acos(1e-6);
  CHECK(diff(t.query(550, 0.3, near), g) < 1e-4);
  // Mirror: ss, pp unchanged, sp, ps negated.
  const JonesReflection a = t.query(600, 0.4, 0.5), b = t.query(600, 0.4, -0.5);
  CHECK(std::abs(a.ss - b.ss) < 1e-15);
  CHECK(std::abs(a.pp - b.pp) < 1e-15);
  CHECK(std::abs(a.sp + b.sp) < 1e-15);
  CHECK(std::abs(a.ps + b.ps) < 1e-15);
}

TEST_CASE("reflection table file round trip and checksum", "[table]") {
  const ReflectionTable t = synthetic_table();
  const auto file = std::filesystem::temp_directory_path() / "plumage_test_table.plt";
  t.save(file);
  const ReflectionTable u = ReflectionTable::load(file);
  CHECK(u.content_hash() == t.content_hash());
  CHECK(u.metadata().crystal == "test-crystal");
  CHECK(u.metadata().period_nm == 190.0);
  CHECK(u.metadata().resolution_nm == 10.0);
  CHECK(u.grid().cos_phi == t.grid().cos_phi);
  CHECK(diff(u.query(450, 0.3, 0.2), t.query(450, 0.3, 0.2)) == 0.0);
  // One flipped byte in the payload is caught.
  {
    std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(-40, std::ios::end);
    char c = 0x5a;
    f.write(&c, 1);
  }
  CHECK_THROWS_WITH(ReflectionTable::load(file), Catch::Contains("checksum"));
  std::filesystem::remove(file);
}

TEST_CASE("reflection table stays passive where the interpolation overshoots toward grazing", "[table]") {
  // A lossless-like crystal: |r| = 1 at every node, the phase turning quickly as k_z → 0 (as a
  // real stack's does near the grazing node). Component-wise cubic interpolation between such
  // nodes and the analytic diag(−1, −1) node overshoots |r| = 1; the query must not.
  TableGrid g = TableGrid::uniform(400, 700, 2, 5, 5);
  ReflectionTable t(g, {"test-crystal", 190.0, "0123456789abcdef", 10.0, "unit test", ""});
  for (std::size_t l = 0; l < 2; ++l)
    for (std::size_t i = 0; i < 5; ++i)
      for (std::size_t j = 0; j < 5; ++j) {
        const double kz = g.cos_theta[i] * g.cos_phi[j];
        const Complex r = std::polar(1.0, kPi - 3.0 * kz);
        t.at(l, i, j) = {r, 0.0, 0.0, r * Complex(0.0, 1.0)};
      }
  // Without the projection this grid reaches σ_max = 1.133 (measured by disabling it).
  double queried = 0.0;
  for (int a = 1; a < 100; ++a)
    for (int b = 1; b < 100; ++b) {
      const double ct = a / 100.0, cp = b / 100.0;
      queried = std::max(queried, largest_singular_value(t.query(550.0, std::acos(ct), std::acos(cp))));
    }
  INFO("largest singular value over the queried grid " << queried);
  CHECK(queried <= 1.0 + 1e-12);
  // Nodes themselves are untouched (σ = 1 exactly there).
  CHECK(largest_singular_value(t.query(400.0, std::acos(g.cos_theta[2]), std::acos(g.cos_phi[3]))) ==
        Approx(1.0).epsilon(1e-12));
}
