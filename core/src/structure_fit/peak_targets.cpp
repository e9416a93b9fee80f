// Peak targets of `plumage fit` (plumage/structure_fit.hpp): a reflectance maximum's position as a
// fitted value, from a window of reflectance samples.
#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "plumage/error.hpp"
#include "plumage/structure_fit.hpp"

namespace plumage {

namespace {

// Samples of one peak window: λ_t + k·step, k = −K … K, K = round(window / (2 step)).
int half_width(const FitTarget& t) { return std::max(1, static_cast<int>(std::lround(0.5 * t.window_nm / t.step_nm))); }

}  // namespace

double fit_target_value(const FitTarget& t) { return t.kind == FitTargetKind::peak ? t.lambda_nm : t.reflectance; }

std::vector<FitTarget> fit_model_samples(const std::vector<FitTarget>& targets) {
  std::vector<FitTarget> out;
  for (const FitTarget& t : targets) {
    if (t.kind == FitTargetKind::reflectance) {
      out.push_back(t);
      continue;
    }
    const int k_max = half_width(t);
    for (int k = -k_max; k <= k_max; ++k) {
      FitTarget s = t;
      s.kind = FitTargetKind::reflectance;
      s.lambda_nm = t.lambda_nm + k * t.step_nm;
      out.push_back(s);
    }
  }
  return out;
}

double parabola_peak_nm(const std::vector<double>& lambda_nm, const std::vector<double>& r) {
  const std::size_t n = lambda_nm.size();
  if (n < 3 || r.size() != n) throw NumericalError("parabola_peak_nm: needs at least 3 samples");
  // Centred and scaled abscissa: the normal equations of a quadratic in raw nm are ill-conditioned.
  const double lo = lambda_nm.front(), hi = lambda_nm.back();
  const double mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
  Eigen::MatrixXd a(n, 3);
  Eigen::VectorXd y(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double u = (lambda_nm[i] - mid) / half;
    a(i, 0) = 1.0, a(i, 1) = u, a(i, 2) = u * u;
    y(i) = r[i];
  }
  const Eigen::Vector3d c = a.colPivHouseholderQr().solve(y);
  const double high_end = r.back() >= r.front() ? hi : lo;
  if (!(c(2) < 0.0)) return high_end;  // no interior maximum
  // A vertex outside the window (the window on the peak's flank) is kept up to one window width
  // beyond it: the fit still sees which way to move; further out the parabola says nothing.
  const double u = -c(1) / (2.0 * c(2));
  return std::clamp(mid + u * half, lo - (hi - lo), hi + (hi - lo));
}

std::vector<double> fit_target_predictions(const std::vector<FitTarget>& targets, const std::vector<double>& sample_r) {
  std::vector<double> out;
  std::size_t at = 0;
  for (const FitTarget& t : targets) {
    if (t.kind == FitTargetKind::reflectance) {
      out.push_back(sample_r.at(at++));
      continue;
    }
    const int k_max = half_width(t);
    std::vector<double> l, r;
    for (int k = -k_max; k <= k_max; ++k) l.push_back(t.lambda_nm + k * t.step_nm), r.push_back(sample_r.at(at++));
    out.push_back(parabola_peak_nm(l, r));
  }
  if (at != sample_r.size()) throw NumericalError("fit: the forward model returned a wrong number of samples");
  return out;
}

}  // namespace plumage
