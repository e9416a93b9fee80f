// write_fit_outputs (plumage/structure_fit.hpp): fit.txt, fit.csv, fit_starts.csv,
// fit_spectrum.csv, fit.png and fitted.yaml of `plumage fit`.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <sstream>

#include "plumage/atomic_file.hpp"
#include "plumage/charts.hpp"
#include "plumage/param_table.hpp"
#include "plumage/structure_fit.hpp"

namespace plumage {

namespace {

const char* polarization_name(FitPolarization p) {
  switch (p) {
    case FitPolarization::s: return "s";
    case FitPolarization::p: return "p";
    default: return "unpolarized";
  }
}

std::string parameters_csv(const FitSpec& spec, const FitResult& r) {
  std::ostringstream csv;
  csv << std::setprecision(10)
      << "# plumage fit " << spec.file.string() << ": value and 1 sigma = sqrt(s^2 (J^T J)^-1), s^2 = chi2/(m - n)\n"
      << "path,value,sigma,lower,upper,start,at_bound,chi2,reduced_chi2,residuals,evaluations,cpu_s,cpu_s_per_evaluation\n";
  for (std::size_t j = 0; j < spec.parameters.size(); ++j) {
    const FitParameter& p = spec.parameters[j];
    csv << p.path << ',' << r.value[j] << ',' << r.sigma[j] << ',' << p.lower << ',' << p.upper << ','
        << r.starts[r.best].start[j] << ',' << (r.at_bound[j] ? "yes" : "no") << ',' << r.chi2 << ','
        << r.reduced_chi2 << ',' << r.residuals << ',' << r.evaluations << ',' << r.cpu_seconds << ','
        << r.cpu_seconds / static_cast<double>(r.evaluations) << '\n';
  }
  return csv.str();
}

std::string starts_csv(const FitSpec& spec, const FitResult& r) {
  std::ostringstream csv;
  csv << std::setprecision(10) << "start,chi2,iterations,converged,best";
  for (const FitParameter& p : spec.parameters) csv << ",start:" << p.path << ",value:" << p.path;
  csv << '\n';
  for (std::size_t k = 0; k < r.starts.size(); ++k) {
    const FitStart& s = r.starts[k];
    csv << k << ',' << s.chi2 << ',' << s.iterations << ',' << (s.converged ? "yes" : "no") << ','
        << (k == r.best ? "yes" : "no");
    for (std::size_t j = 0; j < s.start.size(); ++j) csv << ',' << s.start[j] << ',' << s.value[j];
    csv << '\n';
  }
  return csv.str();
}

std::string spectrum_csv(const FitSpec& spec, const FitResult& r) {
  std::ostringstream csv;
  csv << std::setprecision(10) << "lambda_nm,theta_deg,polarization,R_target,sigma,R_fit\n";
  for (std::size_t i = 0; i < spec.targets.size(); ++i) {
    const FitTarget& t = spec.targets[i];
    if (t.kind != FitTargetKind::reflectance) continue;
    csv << t.lambda_nm << ',' << t.theta_deg << ',' << polarization_name(t.polarization) << ',' << t.reflectance << ','
        << t.sigma << ',' << r.prediction[i] << '\n';
  }
  return csv.str();
}

bool has_peaks(const FitSpec& spec) {
  for (const FitTarget& t : spec.targets)
    if (t.kind == FitTargetKind::peak) return true;
  return false;
}

// Peak targets: the target and fitted peak wavelengths (the vertex of the window's parabola).
std::string peaks_csv(const FitSpec& spec, const FitResult& r) {
  std::ostringstream csv;
  csv << std::setprecision(10) << "lambda_target_nm,theta_deg,polarization,sigma_nm,window_nm,lambda_fit_nm\n";
  for (std::size_t i = 0; i < spec.targets.size(); ++i) {
    const FitTarget& t = spec.targets[i];
    if (t.kind != FitTargetKind::peak) continue;
    csv << t.lambda_nm << ',' << t.theta_deg << ',' << polarization_name(t.polarization) << ',' << t.sigma << ','
        << t.window_nm << ',' << r.prediction[i] << '\n';
  }
  return csv.str();
}

// One panel per (θ, polarization): the target dashed, the fit solid.
void draw_fit(const FitSpec& spec, const FitResult& r, const std::filesystem::path& png) {
  LineChart chart;
  chart.title = "plumage fit " + spec.file.filename().string() + ": target and fitted prediction";
  chart.x_label = "wavelength (nm)";
  chart.y_label = "reflectance";
  for (std::size_t i = 0; i < spec.targets.size(); ++i) {
    const FitTarget& t = spec.targets[i];
    if (t.kind != FitTargetKind::reflectance) continue;  // listed in fit.txt and fit_peaks.csv
    std::ostringstream panel;
    panel << "θ = " << t.theta_deg << "°, " << polarization_name(t.polarization);
    chart.points.push_back({panel.str(), "target", t.lambda_nm, t.reflectance, true});
    chart.points.push_back({panel.str(), "fit", t.lambda_nm, r.prediction[i]});
  }
  draw_line_chart(chart, png);
}

}  // namespace

std::string fit_summary_text(const FitSpec& spec, const StructureForwardModel& model, const FitResult& r) {
  std::ostringstream t;
  t << "plumage fit " << spec.file.string() << "\nmodel: " << model.description() << "\n"
    << "target: " << spec.targets.size() << " values" << (spec.measured.empty() ? "" : " from " + spec.measured.string())
    << "\n";
  t << std::setprecision(6);
  for (std::size_t i = 0; i < spec.targets.size(); ++i) {
    const FitTarget& x = spec.targets[i];
    if (x.kind != FitTargetKind::peak) continue;
    t << "peak at theta " << x.theta_deg << " deg, " << polarization_name(x.polarization) << ": target " << x.lambda_nm
      << " +- " << x.sigma << " nm, fitted " << r.prediction[i] << " nm (parabola over " << x.window_nm << " nm)\n";
  }
  t << "\n";
  for (std::size_t j = 0; j < spec.parameters.size(); ++j) {
    const FitParameter& p = spec.parameters[j];
    t << p.path << " = " << r.value[j] << " +- " << r.sigma[j] << " (1 sigma; bounds [" << p.lower << ", " << p.upper
      << "], file " << p.file_value << ")" << (r.at_bound[j] ? "  AT A BOUND: sigma is not meaningful" : "") << "\n";
  }
  const std::size_t n = spec.parameters.size();
  const bool have_sigma = !r.sigma.empty() && std::isfinite(r.sigma[0]);
  if (n > 1 && (r.covariance_note.empty() || have_sigma)) {
    t << "correlation:\n";
    for (std::size_t j = 0; j < n; ++j) {
      for (std::size_t k = 0; k < n; ++k) t << (k ? " " : "  ") << std::setw(8) << std::setprecision(3) << r.correlation[j * n + k];
      t << "\n";
    }
    t << std::setprecision(6);
  }
  if (!r.covariance_note.empty()) t << (have_sigma ? "uncertainty: " : "no uncertainty: ") << r.covariance_note << "\n";
  t << "chi2 = " << r.chi2 << " over " << r.residuals << " values, reduced chi2 s^2 = " << r.reduced_chi2
    << " (sigma scaled by s)\n\nstarts (best marked *):\n";
  for (std::size_t k = 0; k < r.starts.size(); ++k) {
    const FitStart& s = r.starts[k];
    t << (k == r.best ? " * " : "   ") << k << ": chi2 " << s.chi2 << ", " << s.iterations << " iterations, "
      << (s.converged ? "converged" : "not converged") << " from (";
    for (std::size_t j = 0; j < s.start.size(); ++j) t << (j ? ", " : "") << s.start[j];
    t << ") to (";
    for (std::size_t j = 0; j < s.value.size(); ++j) t << (j ? ", " : "") << s.value[j];
    t << ")\n";
  }
  t << "\ncost: " << r.evaluations << " model evaluations, " << r.cpu_seconds << " s CPU ("
    << r.cpu_seconds / static_cast<double>(r.evaluations) << " s per evaluation), " << r.wall_seconds << " s wall\n";
  return t.str();
}

std::vector<std::string> write_fit_outputs(const FitSpec& spec, const StructureForwardModel& model,
                                           const FitResult& result, const std::filesystem::path& out, bool draw) {
  std::filesystem::create_directories(out);
  // fitted.yaml first: a value the file refuses fails before any other output is written.
  std::ostringstream header;
  header << "# Written by plumage fit " << spec.file.string() << " from " << spec.config.string() << ":\n";
  for (std::size_t j = 0; j < spec.parameters.size(); ++j)
    header << "#   " << spec.parameters[j].path << " = " << format_param_number(result.value[j]) << " +- "
           << result.sigma[j] << " (1 sigma)\n";
  write_text_atomically(out / "fitted.yaml", header.str() + fitted_config_yaml(spec, result.value));
  write_text_atomically(out / "fit.txt", fit_summary_text(spec, model, result));
  write_text_atomically(out / "fit.csv", parameters_csv(spec, result));
  write_text_atomically(out / "fit_starts.csv", starts_csv(spec, result));
  write_text_atomically(out / "fit_spectrum.csv", spectrum_csv(spec, result));
  std::vector<std::string> written{"fitted.yaml", "fit.txt", "fit.csv", "fit_starts.csv", "fit_spectrum.csv"};
  if (has_peaks(spec)) {
    write_text_atomically(out / "fit_peaks.csv", peaks_csv(spec, result));
    written.push_back("fit_peaks.csv");
  }
  const bool any_reflectance = std::any_of(spec.targets.begin(), spec.targets.end(),
                                           [](const FitTarget& t) { return t.kind == FitTargetKind::reflectance; });
  if (draw && any_reflectance) {
    draw_fit(spec, result, out / "fit.png");
    written.push_back("fit.png");
  }
  return written;
}

}  // namespace plumage
