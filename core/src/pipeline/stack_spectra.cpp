// Reflectance spectra of nominal layer stacks (plumage/stack_spectra.hpp).
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

std::string stack_spectra_csv(const std::vector<StackSpectrum>& spectra) {
  std::ostringstream csv;
  csv << "# unpolarized R = (R_s + R_p)/2 of each species' nominal_stack; theta = angle of "
         "incidence on the stack\n"
      << "species,variant,theta_deg,lambda_nm,R_s,R_p,R\n"
      << std::setprecision(10);
  for (const auto& s : spectra) {
    for (const auto& p : s.points) {
      csv << s.species << ',' << s.variant << ',' << p.theta_deg << ',' << p.lambda_nm << ',' << p.r_s << ','
          << p.r_p << ',' << 0.5 * (p.r_s + p.r_p) << '\n';
    }
  }
  return csv.str();
}

void draw_stack_spectra(const std::vector<StackSpectrum>& spectra, const std::filesystem::path& png) {
  LineChart chart;
  chart.title = "Reflectance of the nominal layer stack (unpolarized)";
  chart.x_label = "wavelength (nm)";
  chart.y_label = "reflectance";
  for (const auto& s : spectra) {
    const std::string panel = s.common_name + (s.variant.empty() ? "" : " (" + s.variant + ")");
    for (const auto& p : s.points) {
      std::ostringstream series;
      series << "θ = " << p.theta_deg << "°";
      chart.points.push_back({panel, series.str(), p.lambda_nm, 0.5 * (p.r_s + p.r_p)});
    }
  }
  draw_line_chart(chart, png);
}

}  // namespace plumage
