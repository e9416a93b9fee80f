// Accuracy ladder "bem" (issue 9): the BEM at growing points per wavelength on circular cylinders
// against the exact series (reference/cylinder_series, written independently of the solver):
// relative L2 of the far-field intensity |𝓔|² over 360 directions, the worse polarization — the
// metric of issue 6's acceptance (≤ 1e-3 at the production 30 ppw).
#include <algorithm>
#include <cstdio>
#include <string>

#include "cylinder_check.hpp"
#include "plumage/accuracy_ladder.hpp"

namespace plumage::bem {

namespace {

struct CylinderCase {
  const char* name;
  std::vector<double> radii_nm;  // inner → outer
  std::vector<Material> materials;
  bool quick;                    // part of the quick (CI) ladder
};

}  // namespace

std::vector<LadderPoint> run_bem_ladder(const AccuracyLadder::Options& options) {
  const double lambda_nm = 550.0, theta = 30.0 * std::numbers::pi / 180.0, phi_i = 0.4;
  const std::vector<CylinderCase> cases = {
      {"keratin cylinder r=250nm, 550nm, theta 30deg", {250.0}, {Material::keratin()}, true},
      {"keratin 250nm + melanin shell 100nm, 550nm, theta 30deg", {250.0, 350.0},
       {Material::keratin(), Material::melanin()}, false},
      {"keratin cylinder r=1um, 550nm, theta 30deg", {1000.0}, {Material::keratin()}, false}};
  const std::vector<double> ladder =
      options.quick ? std::vector<double>{8, 16, 32} : std::vector<double>{8, 12, 16, 24, 32, 48};
  const auto phi_o = full_circle(360);
  // Warm-up: one-time set-up (the Hankel tables, thread pool) is not part of any rung's cost.
  {
    BemOptions opt;
    opt.points_per_wavelength = 4;
    opt.incidence = BemOptions::Incidence::plane_wave;
    solve_plane_wave(layered_cylinder({100.0}, {Material::keratin()}, lambda_nm, 4, 8), lambda_nm, theta, phi_i,
                     phi_o, opt);
  }
  std::vector<LadderPoint> points;
  for (const auto& c : cases) {
    if (options.quick && !c.quick) continue;
    // The series, once per polarization (not part of the rungs' cost).
    std::vector<std::complex<double>> m;
    std::vector<double> radii_um;
    for (std::size_t k = 0; k < c.radii_nm.size(); ++k) {
      m.push_back(c.materials[k].index(lambda_nm));
      radii_um.push_back(c.radii_nm[k] / 1000.0);
    }
    const oracle::CylinderSolution series[2] = {oracle::solve_layered(radii_um, m, lambda_nm / 1000.0, theta, 1),
                                                oracle::solve_layered(radii_um, m, lambda_nm / 1000.0, theta, 2)};
    for (double ppw : ladder) {
      BemOptions opt;
      opt.points_per_wavelength = ppw;
      opt.incidence = BemOptions::Incidence::plane_wave;
      opt.method = BemOptions::Method::dense;
      // Polygon vertices from ppw alone (no 64-vertex floor), so that each rung refines geometry
      // and mesh together, as in the convergence table of NOTES.md §4.4.
      const CrossSection cs = layered_cylinder(c.radii_nm, c.materials, lambda_nm, ppw, /*min_vertices=*/8);
      PlaneWaveResult result;
      const RungCost cost = measure_rung([&] { result = solve_plane_wave(cs, lambda_nm, theta, phi_i, phi_o, opt); });
      double error = 0.0;
      for (int pol = 0; pol < 2; ++pol) {
        error = std::max(error, compare_with_series(result.field, pol, series[pol], phi_i, phi_o).intensity_l2);
      }
      LadderPoint pt;
      pt.backend = "bem";
      pt.case_name = c.name;
      char setting[64];
      std::snprintf(setting, sizeof setting, "ppw=%g (N=%d)", ppw, result.sys->mesh.unknowns());
      pt.setting = setting;
      pt.fidelity = ppw;
      pt.reference = "exact cylinder series (plugins/bem/reference)";
      pt.metric = "rel. L2 of |E|^2, 360 directions, worse pol";
      pt.error = error;
      pt.wall_s = cost.wall_s;
      pt.cpu_s = cost.cpu_s;
      if (options.progress) {
        char line[200];
        std::snprintf(line, sizeof line, "%s, %s: error %.3g, %.3g s", c.name, setting, error, cost.wall_s);
        options.progress(line);
      }
      points.push_back(pt);
    }
  }
  return points;
}

}  // namespace plumage::bem
