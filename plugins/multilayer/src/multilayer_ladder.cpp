// Accuracy ladder "multilayer" (issue 9): the plug-in's batched reflection (the production path,
// lane kernel included) on periodic Bragg stacks of growing period count N, against the closed
// form of a periodic stack: the Abelès characteristic matrix of one period raised to the N-th
// power by the Chebyshev identity M^N = U_{N−1}(a) M − U_{N−2}(a) I, a = tr M / 2 (det M = 1),
// U_n(cos ψ) = sin((n+1)ψ)/sin ψ. No recursion over layers is involved in the reference, so it
// is independent of the Airy recursion under test, and it shows whether error accumulates with N.
#include "multilayer_ladder.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "multilayer_reflection.hpp"

namespace plumage::multilayer {

namespace {

using C = std::complex<double>;

struct Mat2 {
  C a, b, c, d;
};

Mat2 operator*(const Mat2& x, const Mat2& y) {
  return {x.a * y.a + x.b * y.c, x.a * y.b + x.b * y.d, x.c * y.a + x.d * y.c, x.c * y.b + x.d * y.d};
}

// q = n cos θ in the medium (Im q ≥ 0: decaying into absorbing layers, e^{−iωt}).
C normal_wavenumber(C n, double sin2_alpha) {
  C q = std::sqrt(n * n - sin2_alpha);
  if (q.imag() < 0.0) q = -q;
  return q;
}

// Admittance for the s (E-field) and p (H-field) reflection coefficients of stack_solver.hpp:
// Y_s = q, Y_p = q / ε; a single interface then gives (Y_0 − Y_1)/(Y_0 + Y_1) for both.
C admittance(C n, double sin2_alpha, bool p) {
  const C q = normal_wavenumber(n, sin2_alpha);
  return p ? q / (n * n) : q;
}

// Characteristic matrix of one layer, [E; H]_top = M [E; H]_bottom, time convention e^{−iωt}.
Mat2 layer_matrix(C n, double d_nm, double k0, double sin2_alpha, bool p) {
  const C delta = k0 * normal_wavenumber(n, sin2_alpha) * d_nm;
  const C y = admittance(n, sin2_alpha, p);
  const C cs = std::cos(delta), sn = std::sin(delta);
  const C i(0.0, 1.0);
  return {cs, -i * sn / y, -i * y * sn, cs};
}

// r of N periods (layer A then layer B, A on top) between ambient n0 and substrate ns.
C periodic_stack_r(C n0, C na, double da, C nb, double db, C ns, int periods, double lambda_nm,
                   double sin2_alpha, bool p) {
  const double k0 = 2.0 * M_PI / lambda_nm;
  const Mat2 m = layer_matrix(na, da, k0, sin2_alpha, p) * layer_matrix(nb, db, k0, sin2_alpha, p);
  const C half_trace = 0.5 * (m.a + m.d);
  const C psi = std::acos(half_trace);
  const C s = std::sin(psi);
  auto u = [&](int n) { return n < 0 ? C(n == -1 ? 0.0 : -1.0) : std::sin(C(n + 1) * psi) / s; };
  const C u1 = u(periods - 1), u2 = u(periods - 2);
  const Mat2 mn{u1 * m.a - u2, u1 * m.b, u1 * m.c, u1 * m.d - u2};
  const C y0 = admittance(n0, sin2_alpha, p), ys = admittance(ns, sin2_alpha, p);
  const C bb = mn.a + mn.b * ys, cc = mn.c + mn.d * ys;
  return (y0 * bb - cc) / (y0 * bb + cc);
}

struct StackCase {
  const char* name;
  Material a, b;
  double da_nm, db_nm;
};

}  // namespace

std::vector<LadderPoint> MultilayerLadder::run(const Options& options) const {
  const std::vector<StackCase> cases = {
      {"keratin 100 nm / air 120 nm on keratin", Material::keratin(), Material::air(), 100.0, 120.0},
      {"melanin 90 nm / keratin 100 nm on keratin", Material::melanin(), Material::keratin(), 90.0, 100.0}};
  const std::vector<int> ladder = options.quick ? std::vector<int>{1, 4, 16} : std::vector<int>{1, 2, 4, 8, 16, 32, 64};
  const std::vector<double> angles_deg = {0.0, 30.0, 60.0, 85.0};
  const int wavelengths = 31;  // 400…700 nm in 10 nm steps
  const MultilayerReflection model;
  std::vector<LadderPoint> points;
  for (const auto& sc : cases) {
    for (int periods : ladder) {
      LayerProfile profile;
      profile.ambient = Material::air();
      profile.substrate = Material::keratin();
      for (int k = 0; k < periods; ++k) {
        profile.layers.push_back({sc.a, sc.da_nm});
        profile.layers.push_back({sc.b, sc.db_nm});
      }
      std::vector<LocalReflection::Request> requests;
      for (double deg : angles_deg) {
        for (int w = 0; w < wavelengths; ++w) {
          requests.push_back({400.0 + 10.0 * w, {deg * M_PI / 180.0, 0.0}, &profile});
        }
      }
      std::vector<JonesReflection> out(requests.size());
      // Enough repeats for a measurable time; the rung's cost is one batch.
      const int repeats = std::max(1, 2000 / periods);
      const RungCost cost = measure_rung([&] {
        for (int r = 0; r < repeats; ++r) model.reflect(requests, out);
      });
      double error = 0.0;
      for (std::size_t i = 0; i < requests.size(); ++i) {
        const double lambda = requests[i].lambda_nm;
        const double sin_t = std::sin(requests[i].incidence.theta_rad);
        const C n0 = profile.ambient.index(lambda), ns = profile.substrate.index(lambda);
        const C na = sc.a.index(lambda), nb = sc.b.index(lambda);
        for (bool p : {false, true}) {
          const C ref = periodic_stack_r(n0, na, sc.da_nm, nb, sc.db_nm, ns, periods, lambda, sin_t * sin_t, p);
          error = std::max(error, std::abs((p ? out[i].pp : out[i].ss) - ref));
        }
      }
      LadderPoint pt;
      pt.backend = "multilayer";
      pt.case_name = sc.name;
      pt.setting = "N=" + std::to_string(periods);
      pt.fidelity = periods;
      pt.reference = "closed form (Abeles matrix, Chebyshev power)";
      pt.metric = "max |r - r_ref|";
      pt.error = error;
      pt.wall_s = cost.wall_s / repeats;
      pt.cpu_s = cost.cpu_s / repeats;
      if (options.progress) {
        char line[160];
        std::snprintf(line, sizeof line, "%s, %s: error %.3g, %.3g s", sc.name, pt.setting.c_str(), error, pt.wall_s);
        options.progress(line);
      }
      points.push_back(pt);
    }
  }
  return points;
}

}  // namespace plumage::multilayer
