// Two tables of the same grid, entry by entry (NOTES.md §5: a speed-up that should not change the
// outputs beyond rounding is checked on whole tables built by the old and the new plug-in). Not
// part of any suite (hidden tag):
//   RCWA_TABLE_A=old.plt RCWA_TABLE_B=new.plt test_rcwa "[table-diff]"
// prints max |ΔJ_ab| over all entries and components, and max |Δ|J_ab|²| and where it is.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "plumage/reflection_table.hpp"

using namespace plumage;

TEST_CASE("rcwa: two tables of one grid, entry by entry", "[.][table-diff]") {
  const char* file_a = std::getenv("RCWA_TABLE_A");
  const char* file_b = std::getenv("RCWA_TABLE_B");
  if (!file_a || !file_b) FAIL("set RCWA_TABLE_A and RCWA_TABLE_B");
  const ReflectionTable a = ReflectionTable::load(file_a), b = ReflectionTable::load(file_b);
  const TableGrid &ga = a.grid(), &gb = b.grid();
  REQUIRE(ga.lambda_nm == gb.lambda_nm);
  REQUIRE(ga.cos_theta == gb.cos_theta);
  REQUIRE(ga.cos_phi == gb.cos_phi);
  double max_dj = 0.0, max_dpower = 0.0, at_lambda = 0.0, at_cos_theta = 0.0, at_cos_phi = 0.0;
  std::size_t entries = 0, identical = 0;
  for (std::size_t il = 0; il < ga.lambda_nm.size(); ++il)
    for (std::size_t it = 0; it < ga.cos_theta.size(); ++it)
      for (std::size_t ip = 0; ip < ga.cos_phi.size(); ++ip) {
        const JonesReflection &x = a.at(il, it, ip), &y = b.at(il, it, ip);
        const Complex jx[4] = {x.ss, x.sp, x.ps, x.pp}, jy[4] = {y.ss, y.sp, y.ps, y.pp};
        bool same = true;
        for (int k = 0; k < 4; ++k) {
          max_dj = std::max(max_dj, std::abs(jx[k] - jy[k]));
          const double dpower = std::abs(std::norm(jx[k]) - std::norm(jy[k]));
          if (dpower > max_dpower)
            max_dpower = dpower, at_lambda = ga.lambda_nm[il], at_cos_theta = ga.cos_theta[it], at_cos_phi = ga.cos_phi[ip];
          same = same && jx[k] == jy[k];
        }
        ++entries;
        identical += same ? 1 : 0;
      }
  std::printf("%zu entries (%zu bit-identical): max |dJ| %.3g, max |d|J|^2| %.3g (at %.1f nm, cos theta %.3f, cos phi %.3f)\n",
              entries, identical, max_dj, max_dpower, at_lambda, at_cos_theta, at_cos_phi);
  CHECK(entries > 0);
}
