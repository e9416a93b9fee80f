// Reflectance spectra of nominal layer stacks (plumage/stack_spectra.hpp).
#include <algorithm>
#include <cmath>
#include <complex>
#include <iomanip>
#include <optional>
#include <sstream>

#include "plumage/charts.hpp"
#include "plumage/conventions.hpp"
#include "plumage/cross_section.hpp"
#include "plumage/stack_spectra.hpp"

namespace plumage {

namespace {

// The stack a species' spectrum is drawn from: its nominal_stack; for a variant that changed its
// structure but not its nominal_stack (SpeciesConfig::nominal_stack_from_structure), the stack
// under the apex (highest top vertex, largest z) of its own instance 0, so that the spectrum is the
// variant's and not the base's. Empty when there is neither (or the structure has no layered model).
std::optional<LayerProfile> spectrum_stack(const SpeciesConfig& s) {
  if (s.nominal_stack) return s.nominal_stack;
  if (!s.nominal_stack_from_structure || !s.structure) return std::nullopt;
  const CrossSection section = s.structure->generate(0);
  if (!section.layered || section.top.empty()) return std::nullopt;
  std::size_t apex = 0;
  for (std::size_t i = 1; i < section.top.size(); ++i)
    if (section.top[i].z > section.top[apex].z) apex = i;
  return layer_profile_at(section, apex);
}

// One species' unpolarised R at `theta_deg` (λ, R), in λ order.
std::pair<std::vector<double>, std::vector<double>> unpolarised_at(const StackSpectrum& s, double theta_deg) {
  std::pair<std::vector<double>, std::vector<double>> out;
  for (const auto& p : s.points) {
    if (std::abs(p.theta_deg - theta_deg) > 1e-6) continue;
    out.first.push_back(p.lambda_nm);
    out.second.push_back(0.5 * (p.r_s + p.r_p));
  }
  return out;
}

}  // namespace

std::vector<StackSpectrum> nominal_stack_spectra(const std::vector<SpeciesConfig>& species,
                                                 const std::vector<double>& lambdas_nm,
                                                 const std::vector<double>& thetas_deg,
                                                 const PreparationOptions& preparation,
                                                 std::vector<std::filesystem::path>* skipped) {
  std::vector<StackSpectrum> out;
  for (const auto& s : species) {
    const std::optional<LayerProfile> stack = spectrum_stack(s);
    if (!stack || !s.reflection) {
      if (skipped) skipped->push_back(s.file);
      continue;
    }
    prepare_species(s, preparation);
    std::vector<LocalReflection::Request> requests;
    for (double t : thetas_deg) {
      for (double l : lambdas_nm) requests.push_back({l, {0.0, deg_to_rad(t)}, &*stack});
    }
    std::vector<JonesReflection> r(requests.size());
    s.reflection->reflect(requests, r);
    StackSpectrum spectrum{s.species, s.variant, s.common_name, {}};
    for (std::size_t i = 0; i < requests.size(); ++i) {
      // θ as the model saw it (degrees → radians → degrees), so the table states what was computed.
      spectrum.points.push_back({rad_to_deg(requests[i].incidence.phi_local_rad), requests[i].lambda_nm,
                                 std::norm(r[i].ss), std::norm(r[i].pp)});
    }
    out.push_back(std::move(spectrum));
  }
  return out;
}

std::string stack_spectra_csv(const std::vector<StackSpectrum>& spectra, const MeasuredSpectrum* measured) {
  std::ostringstream csv;
  csv << "# unpolarized R = (R_s + R_p)/2 of each species' nominal_stack; theta = angle of "
         "incidence on the stack\n"
      << "species,variant,theta_deg,lambda_nm,R_s,R_p,R" << (measured ? ",R_measured\n" : "\n")
      << std::setprecision(10);
  for (const auto& s : spectra) {
    for (const auto& p : s.points) {
      csv << s.species << ',' << s.variant << ',' << p.theta_deg << ',' << p.lambda_nm << ',' << p.r_s << ','
          << p.r_p << ',' << 0.5 * (p.r_s + p.r_p);
      if (measured) {
        const MeasuredCurve* curve = measured_curve_at(*measured, p.theta_deg);
        const auto r = curve ? measured_reflectance_at(*curve, p.lambda_nm) : std::nullopt;
        csv << ',';
        if (r) csv << *r;
      }
      csv << '\n';
    }
  }
  return csv.str();
}

void draw_stack_spectra(const std::vector<StackSpectrum>& spectra, const std::filesystem::path& png,
                        const MeasuredSpectrum* measured) {
  LineChart chart;
  chart.title = "Reflectance of the nominal layer stack (unpolarized; one fixed stack, not the whole barbule)";
  chart.x_label = "wavelength (nm)";
  chart.y_label = "reflectance";
  for (const auto& s : spectra) {
    const std::string panel = s.common_name + (s.variant.empty() ? "" : " (" + s.variant + ")");
    for (const auto& p : s.points) {
      std::ostringstream series;
      series << "θ = " << p.theta_deg << "°";
      chart.points.push_back({panel, series.str(), p.lambda_nm, 0.5 * (p.r_s + p.r_p)});
    }
    if (!measured) continue;
    for (const auto& c : measured->curves) {
      std::ostringstream series;
      series << "measured " << c.label;
      if (c.theta_deg) series << " (θ = " << *c.theta_deg << "°)";
      for (std::size_t i = 0; i < c.lambda_nm.size(); ++i)
        chart.points.push_back({panel, series.str(), c.lambda_nm[i], c.reflectance[i], true});
    }
  }
  draw_line_chart(chart, png);
}

}  // namespace plumage

namespace plumage {

std::vector<double> with_measured_angles(std::vector<double> thetas_deg, const MeasuredSpectrum& measured) {
  for (const auto& c : measured.curves) {
    if (!c.theta_deg) continue;
    const bool present = std::any_of(thetas_deg.begin(), thetas_deg.end(),
                                     [&](double t) { return std::abs(t - *c.theta_deg) <= 1e-6; });
    if (!present) thetas_deg.push_back(*c.theta_deg);
  }
  return thetas_deg;
}

std::vector<MeasuredStackComparison> compare_stack_spectra(const std::vector<StackSpectrum>& spectra,
                                                           const MeasuredSpectrum& measured) {
  std::vector<MeasuredStackComparison> out;
  for (const auto& s : spectra) {
    for (const auto& c : measured.curves) {
      if (!c.theta_deg) continue;
      const auto [lambda, r] = unpolarised_at(s, *c.theta_deg);
      if (lambda.empty()) continue;
      out.push_back({s.species, s.variant, s.common_name, c.label, *c.theta_deg, compare_spectra(lambda, r, c)});
    }
  }
  return out;
}

std::string measured_comparison_text(const std::vector<MeasuredStackComparison>& comparisons) {
  std::ostringstream text;
  text << std::fixed;
  for (const auto& m : comparisons) {
    const auto& c = m.comparison;
    text << "measured: " << m.species << (m.variant.empty() ? "" : " (" + m.variant + ")") << " vs " << m.curve
         << std::setprecision(1) << ", theta " << m.theta_deg << " deg: peak predicted " << c.predicted_peak_nm
         << " nm, measured " << c.measured_peak_nm << " nm, difference " << std::showpos << c.peak_difference_nm
         << std::noshowpos << " nm; RMS error " << std::setprecision(4) << c.rms_error << ", correlation "
         << std::setprecision(3) << c.correlation << " (" << c.points << " wavelengths, " << std::setprecision(0)
         << c.common_from_nm << "-" << c.common_to_nm << " nm)\n";
  }
  return text.str();
}

}  // namespace plumage
