// `plumage simulate` as a library (paper §4): a species' geometry → the far fields of every
// instance for each work unit (λ, ω_i) → a FarFieldSet (far_field_set.hpp), and what is made of
// one: the Eq. 10 pattern CSV, the 2D differential scattering width over the full circle, and a
// Fig. 7-style picture of the colour along the cone.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "plumage/far_field_set.hpp"
#include "plumage/local_reflection.hpp"
#include "plumage/species_config.hpp"

namespace plumage {

struct SimulationRequest {
  std::vector<double> lambdas_nm;       // empty: the config's simulation wavelengths
  std::vector<double> theta_deg{0.0};   // incident θ_i, each in [0, 90)
  std::vector<double> phi_deg{0.0};     // incident φ_i, each in (−90, 90)
  int instances = 0;                    // 0: the config's
  // pattern: the 400-bin pattern set on (−90°, 90°) plus the projected set (what a
  // characterisation fits); full_circle: 360 azimuths in 1° steps over (−180°, 180°] (validation
  // bodies, full-wave solvers only).
  enum class Directions { pattern, full_circle };
  Directions directions = Directions::pattern;
  PreparationOptions preparation;       // for the species' local reflection (prepare_species)
};

struct SimulationCallbacks {
  std::function<void(std::size_t total)> started;                     // instances prepared, units begin
  std::function<void(std::size_t done, std::size_t total)> progress;  // after every work unit
};

// Prepares the species' models, generates and validates every instance (an invalid one is
// refused, never solved), prepares each instance once for the solver, and solves every unit with
// instance n of N at φ_i + δ_n (δ spread linearly over ±azimuth_jitter_deg, spec §1.1), oneTBB
// over instances. The run's warnings (diagnostics.hpp) go into the set's metadata. A request out
// of range is a ConfigError located at the `plumage simulate` flag that sets it.
FarFieldSet simulate(const SpeciesConfig& config, const SimulationRequest& request,
                     const SimulationCallbacks& callbacks = {});

// The instance-mean reflectance density per radian of φ_o (Eq. 10) of every unit, pattern
// directions only, pol 1, 2 and mean; written atomically.
void write_pattern_csv(const FarFieldSet& set, const std::filesystem::path& file);

// The instance-mean 2D differential scattering width dσ/dφ_o = cos θ_i |𝓔(φ_o)|² (nm per radian)
// and σ_2D = 2π dσ/dφ_o of a full-circle set, with the normalisation in the file's header.
void write_scattering_width_csv(const FarFieldSet& set, const std::filesystem::path& file);

// Fig. 7: colour along the cone for the instance mean and three instances, and the mean density
// at four wavelengths, at the set's first incident direction (scripts/plot_pattern.py). Needs at
// least two wavelengths (Error otherwise).
void draw_cone_colours(const FarFieldSet& set, const std::filesystem::path& png, const std::string& title);

}  // namespace plumage
