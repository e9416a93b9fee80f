// Accuracy ladder "rcwa": rungs (M, slices per rod diameter) = (2, 3), (3, 6), (5, 12), (7, 24) and
// (5, 12) Richardson-extrapolated from 6 and 12 slices,
// on a crystal (default mallard-green) against the finest rung (10, 48); metric: max over
// 3 wavelengths × 2 conical incidences and the four Jones elements of ||J_ab|² − |J_ab,ref|²|
// (the issue-5 acceptance metric of the FDTD ladder). The staircase converges as 1/slices²
// (NOTES.md §2), so the finest rung is a reference to ~1e-4; the lamellar limit, where the
// method is exact, is checked by the tests instead.
#include "rcwa_ladder.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "plumage/crystal_cell.hpp"
#include "plumage/error.hpp"
#include "solver.hpp"

namespace plumage::rcwa {

const ParamTable<LadderParams>& ladder_params() {
  static const auto table = ParamTable<LadderParams>{}.text(
      "crystal", &LadderParams::crystal, "configs/crystals/mallard-green.yaml", "crystal cell of the ladder");
  return table;
}

namespace {

struct Rung {
  int harmonics, slices;
  bool extrapolated = false;  // Richardson from slices/2 and slices
};

struct Sample {
  double lambda_nm, theta, phi;
};

std::vector<JonesReflection> solve_all(const CrystalCell& c, const Rung& r, const std::vector<Sample>& samples) {
  const SlicedCell sliced = slice_crystal(c, r.slices);
  const SlicedCell half = slice_crystal(c, std::max(1, r.slices / 2));
  std::vector<JonesReflection> out;
  for (const Sample& s : samples)
    out.push_back(r.extrapolated ? solve_entry_extrapolated(half, sliced, s.lambda_nm, s.theta, s.phi, {r.harmonics, true}).jones
                                 : solve_entry(sliced, s.lambda_nm, s.theta, s.phi, {r.harmonics, true}).jones);
  return out;
}

double max_power_difference(const std::vector<JonesReflection>& a, const std::vector<JonesReflection>& b) {
  double e = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
    e = std::max({e, std::abs(std::norm(a[i].ss) - std::norm(b[i].ss)), std::abs(std::norm(a[i].sp) - std::norm(b[i].sp)),
                  std::abs(std::norm(a[i].ps) - std::norm(b[i].ps)), std::abs(std::norm(a[i].pp) - std::norm(b[i].pp))});
  return e;
}

}  // namespace

std::vector<LadderPoint> run_rcwa_ladder(const AccuracyLadder::Options& options, const std::string& crystal_file) {
  if (!std::filesystem::exists(crystal_file))
    throw Error("accuracy ladder 'rcwa': " + crystal_file + " not found (run from the source tree or set crystal:)");
  const CrystalCell c = load_crystal_cell(crystal_file);
  std::vector<Sample> samples;
  for (double l : {450.0, 545.0, 650.0})
    for (auto [t, p] : {std::pair{0.3, 0.5}, {0.7, 0.9}}) samples.push_back({l, t, p});
  std::vector<Rung> rungs = {{2, 3}, {3, 6}, {5, 12}, {5, 12, true}, {7, 24}};
  const Rung finest = options.quick ? Rung{7, 24} : Rung{10, 48};
  if (options.quick) rungs.pop_back();
  const std::vector<JonesReflection> ref = solve_all(c, finest, samples);
  std::vector<LadderPoint> points;
  for (const Rung& r : rungs) {
    std::vector<JonesReflection> got;
    const RungCost cost = measure_rung([&] { got = solve_all(c, r, samples); });
    LadderPoint pt;
    pt.backend = "rcwa";
    pt.case_name = c.name + ", 3 lambda x 2 conical angles";
    pt.setting = "M=" + std::to_string(r.harmonics) + " slices=" + std::to_string(r.slices) +
                 (r.extrapolated ? " Richardson(" + std::to_string(r.slices / 2) + ")" : "");
    pt.fidelity = r.slices;
    pt.reference = "finest rung M=" + std::to_string(finest.harmonics) + " slices=" + std::to_string(finest.slices);
    pt.metric = "max ||J_ab|^2 - |J_ab,ref|^2|";
    pt.error = max_power_difference(got, ref);
    pt.wall_s = cost.wall_s;
    pt.cpu_s = cost.cpu_s;
    if (options.progress) options.progress("rcwa " + pt.setting + ": error " + std::to_string(pt.error));
    points.push_back(pt);
  }
  return points;
}

}  // namespace plumage::rcwa
