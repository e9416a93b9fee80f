// `plumage spectra` as a library: reflectance spectra of each species' nominal local layer stack
// through the species' own LocalReflection plug-in — the quick look at what colour a species'
// structure selects, before any geometry or far-field simulation.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "plumage/local_reflection.hpp"
#include "plumage/measured_spectrum.hpp"
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

// "species,variant,theta_deg,lambda_nm,R_s,R_p,R" with a header comment; with a measurement
// (its angles resolved: with_measurement_angle) also "R_measured", the measured curve at that θ
// interpolated linearly at λ (empty outside its range or without a curve at that θ).
std::string stack_spectra_csv(const std::vector<StackSpectrum>& spectra, const MeasuredSpectrum* measured = nullptr);

// One panel per species, one curve per θ (unpolarised R against λ); with a measurement (angles
// resolved) its curves dashed in every panel. Throws Error when matplotlib fails.
void draw_stack_spectra(const std::vector<StackSpectrum>& spectra, const std::filesystem::path& png,
                        const MeasuredSpectrum* measured = nullptr);

// The θ of each measured curve (angles resolved) that is not among `thetas_deg`, appended to it:
// the prediction is computed at every angle measured.
std::vector<double> with_measured_angles(std::vector<double> thetas_deg, const MeasuredSpectrum& measured);

struct MeasuredStackComparison {
  std::string species, variant, common_name;
  std::string curve;  // the measured curve's label
  double theta_deg = 0.0;
  SpectrumComparison comparison;
};

// Each species' unpolarised spectrum against each measured curve (angles resolved) at the same θ.
// Throws Error when a curve shares fewer than 3 wavelengths with the prediction.
std::vector<MeasuredStackComparison> compare_stack_spectra(const std::vector<StackSpectrum>& spectra,
                                                           const MeasuredSpectrum& measured);

// One line per comparison: species, θ, both peaks, their difference (nm), RMS error, correlation.
std::string measured_comparison_text(const std::vector<MeasuredStackComparison>& comparisons);

}  // namespace plumage
