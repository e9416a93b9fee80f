// A predicted spectrum against a measured one (plumage/measured_spectrum.hpp): peak positions,
// RMS error and correlation on the predicted wavelengths inside the common range.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "plumage/error.hpp"
#include "plumage/input_file.hpp"
#include "plumage/measured_spectrum.hpp"

namespace plumage {

namespace {

// The peak of samples (x strictly increasing): the largest sample, refined by the vertex of the
// parabola through it and its neighbours (the sample itself at an end or for a flat top).
double parabolic_peak(const std::vector<double>& x, const std::vector<double>& y) {
  std::size_t m = 0;
  for (std::size_t i = 1; i < y.size(); ++i)
    if (y[i] > y[m]) m = i;
  if (m == 0 || m + 1 == y.size()) return x[m];
  const double x0 = x[m - 1], x1 = x[m], x2 = x[m + 1];
  const double y0 = y[m - 1], y1 = y[m], y2 = y[m + 1];
  // Vertex of the Lagrange parabola through three unevenly spaced points.
  const double d0 = (y1 - y0) / (x1 - x0), d1 = (y2 - y1) / (x2 - x1);
  const double curvature = (d1 - d0) / (x2 - x0);
  if (!(curvature < 0)) return x1;
  return 0.5 * (x0 + x1) - d0 / (2.0 * curvature);
}

}  // namespace

std::optional<double> measured_reflectance_at(const MeasuredCurve& measured, double lambda_nm) {
  const auto& l = measured.lambda_nm;
  if (l.empty() || lambda_nm < l.front() || lambda_nm > l.back()) return std::nullopt;
  const auto hi = std::lower_bound(l.begin(), l.end(), lambda_nm);
  const std::size_t j = static_cast<std::size_t>(hi - l.begin());
  if (l[j] == lambda_nm) return measured.reflectance[j];
  const double t = (lambda_nm - l[j - 1]) / (l[j] - l[j - 1]);
  return (1.0 - t) * measured.reflectance[j - 1] + t * measured.reflectance[j];
}

SpectrumComparison compare_spectra(const std::vector<double>& predicted_lambda_nm,
                                   const std::vector<double>& predicted_reflectance, const MeasuredCurve& measured) {
  if (predicted_lambda_nm.size() != predicted_reflectance.size())
    throw Error("compare_spectra: " + std::to_string(predicted_lambda_nm.size()) + " wavelengths but " +
                std::to_string(predicted_reflectance.size()) + " reflectances");
  SpectrumComparison out;
  std::vector<double> lp, rp, rm;  // predicted λ, predicted R, measured R resampled, in the common range
  for (std::size_t i = 0; i < predicted_lambda_nm.size(); ++i) {
    if (const auto m = measured_reflectance_at(measured, predicted_lambda_nm[i])) {
      lp.push_back(predicted_lambda_nm[i]);
      rp.push_back(predicted_reflectance[i]);
      rm.push_back(*m);
    }
  }
  if (lp.size() < 3)
    throw Error("the measured spectrum (" + measured.label + ") shares " + std::to_string(lp.size()) +
                " of the predicted wavelengths; at least 3 are needed for a comparison");
  out.points = lp.size();
  out.common_from_nm = lp.front();
  out.common_to_nm = lp.back();
  // The measured peak from its own samples inside the common range, not the resampled ones:
  // resampling onto a coarse prediction grid would move it.
  std::vector<double> lm_in, rm_in;
  for (std::size_t j = 0; j < measured.lambda_nm.size(); ++j) {
    if (measured.lambda_nm[j] >= out.common_from_nm && measured.lambda_nm[j] <= out.common_to_nm) {
      lm_in.push_back(measured.lambda_nm[j]);
      rm_in.push_back(measured.reflectance[j]);
    }
  }
  out.predicted_peak_nm = parabolic_peak(lp, rp);
  out.measured_peak_nm = lm_in.size() >= 3 ? parabolic_peak(lm_in, rm_in) : parabolic_peak(lp, rm);
  out.peak_difference_nm = out.measured_peak_nm - out.predicted_peak_nm;
  const double n = static_cast<double>(lp.size());
  double sum_sq = 0, mean_p = 0, mean_m = 0;
  for (std::size_t i = 0; i < lp.size(); ++i) {
    sum_sq += (rm[i] - rp[i]) * (rm[i] - rp[i]);
    mean_p += rp[i] / n;
    mean_m += rm[i] / n;
  }
  out.rms_error = std::sqrt(sum_sq / n);
  double cov = 0, var_p = 0, var_m = 0;
  for (std::size_t i = 0; i < lp.size(); ++i) {
    cov += (rp[i] - mean_p) * (rm[i] - mean_m);
    var_p += (rp[i] - mean_p) * (rp[i] - mean_p);
    var_m += (rm[i] - mean_m) * (rm[i] - mean_m);
  }
  out.correlation = var_p > 0 && var_m > 0 ? cov / std::sqrt(var_p * var_m) : 0.0;
  return out;
}

MeasuredSpectrum with_measurement_angle(MeasuredSpectrum measured, std::optional<double> theta_deg) {
  const bool any_angle = std::any_of(measured.curves.begin(), measured.curves.end(),
                                     [](const MeasuredCurve& c) { return c.theta_deg.has_value(); });
  if (any_angle && theta_deg) {
    std::erase_if(measured.curves,
                  [&](const MeasuredCurve& c) { return !c.theta_deg || std::abs(*c.theta_deg - *theta_deg) > 1e-6; });
    if (measured.curves.empty()) {
      std::ostringstream what;
      what << "no measured curve at theta = " << *theta_deg << "°";
      throw InputFileError(measured.file.string(), what.str());
    }
    return measured;
  }
  for (auto& c : measured.curves) {
    if (c.theta_deg) continue;
    c.theta_deg = theta_deg.value_or(0.0);
    if (!theta_deg) measured.notes.push_back(c.label + ": no angle in the file; normal incidence (0°) assumed");
  }
  return measured;
}

const MeasuredCurve* measured_curve_at(const MeasuredSpectrum& measured, double theta_deg) {
  for (const auto& c : measured.curves)
    if (c.theta_deg && std::abs(*c.theta_deg - theta_deg) <= 1e-6) return &c;
  return nullptr;
}

}  // namespace plumage
