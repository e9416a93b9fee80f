// `plumage spectra` as a library: reflectance spectra of each species' nominal local layer stack
// through the species' own LocalReflection plug-in — the quick look at what colour a species'
// structure selects, before any geometry or far-field simulation.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "plumage/local_reflection.hpp"
#include "plumage/species_config.hpp"

namespace plumage {

struct StackSpectrumPoint {
  double theta_deg = 0.0;  // angle of incidence on the stack
  double lambda_nm = 0.0;
  double r_s = 0.0, r_p = 0.0;  // |r_ss|², |r_pp|²; unpolarised R = (R_s + R_p)/2
};

struct StackSpectrum {
  std::string species, variant, common_name;
  std::vector<StackSpectrumPoint> points;  // θ-major, then λ
};

// One spectrum per species that has a nominal_stack and a reflection (others are skipped: their
// files are listed in `skipped`), each θ in degrees at each λ. Prepares each species' reflection
// first (prepare_species).
std::vector<StackSpectrum> nominal_stack_spectra(const std::vector<SpeciesConfig>& species,
                                                 const std::vector<double>& lambdas_nm,
                                                 const std::vector<double>& thetas_deg,
                                                 const PreparationOptions& preparation,
                                                 std::vector<std::filesystem::path>* skipped = nullptr);

// "species,variant,theta_deg,lambda_nm,R_s,R_p,R" with a header comment.
std::string stack_spectra_csv(const std::vector<StackSpectrum>& spectra);

// One panel per species, one curve per θ (unpolarised R against λ). Throws Error when matplotlib fails.
void draw_stack_spectra(const std::vector<StackSpectrum>& spectra, const std::filesystem::path& png);

}  // namespace plumage
