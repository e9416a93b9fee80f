// One camera path of the hero-wavelength spectral path tracer (Wilkie et al. 2014): four
// wavelengths per path, the path sampled with the hero's (λ_0) BSDF, the others weighted by the
// balance heuristic over the four wavelengths' path pdfs (one-sample MIS over which wavelength is
// the hero); next-event estimation for every light, combined with BSDF sampling by the power
// heuristic for area and environment lights; Russian roulette after a few vertices.
//
// Materials are switched on SceneMaterial::Kind (no virtual call per sample). FeatherBsdf is
// evaluated the physical way round, ω_i toward the light and ω_o toward the viewer
// (feather_bsdf.hpp): the fitted mean BRDF is not reciprocal (docs/validation.md "BSDF"), so the
// common shortcut of a renderer (one lookup at the viewer direction used as "ω_i", as Mitsuba's
// BSDF interface does) would render a different material. Per hit: one Incident per λ at the
// viewer direction (the sampling proposal and its pdf), one per λ per light sample and per
// sampled direction (the values); see NOTES.md.
#pragma once

#include <cstdint>
#include <vector>

#include "embree_scene.hpp"
#include "incident_cache.hpp"
#include "plumage/material_warnings.hpp"
#include "plumage/random.hpp"
#include "plumage/scene.hpp"
#include "settings.hpp"
#include "spectral_tables.hpp"

namespace plumage::pathtracer {

// Of one watched (material, warning code) pair: the feather BSDF evaluations whose incident
// direction falls where the characterisation raised the code (plumage/material_warnings.hpp),
// weighted by the path throughput times f·|cos θ| (mean over the four wavelengths), and all of
// the material's evaluations.
struct WarningTally {
  double weight_in = 0.0, weight_total = 0.0;
  std::uint64_t evaluations_in = 0, evaluations = 0;
};

// Per-tile state: counters and the Incident memo (one per tile, so no sharing between threads;
// the render sums the tiles' tallies in tile order, so the totals do not depend on threads).
struct PathCounters {
  std::uint64_t rays = 0;
  std::uint64_t feather_points = 0, feather_mean = 0;
  std::vector<WarningTally> warnings;  // per Integrator::watched() entry
  IncidentCache cache;
};

// A material's warning code that says where it was raised, watched during the render.
struct WatchedWarning {
  std::uint32_t material = 0;  // index into Scene::materials
  MaterialWarning warning;
};

// The random numbers of one camera sample: a counter-based stream keyed by (seed, pixel, sample),
// so every path is reproducible whatever thread traces it.
class PathSampler {
 public:
  PathSampler(std::uint64_t seed, std::uint64_t pixel, std::uint64_t sample)
      : stream_(splitmix64(seed) ^ splitmix64(pixel * 0x9e3779b97f4a7c15ULL + 0x2545f4914f6cdd1dULL) ^
                splitmix64(splitmix64(sample + 0x632be59bd9b4e019ULL))) {}
  double next() { return stream_.uniform(); }

 private:
  RandomStream stream_;
};

class Integrator {
 public:
  Integrator(const Scene& scene, const Settings& settings, const EmbreeScene& embree,
             const SpectralTables& tables);

  // Radiance arriving along −dir at the camera from the ray (origin, dir), at `lambda` (λ_0 the
  // hero). `spread_rad`: the ray cone's spread angle per unit distance (pixel footprint, LOD).
  Spectrum4 trace(V3 origin, V3 dir, double spread_rad, const Spectrum4& lambda, PathSampler& rng,
                  PathCounters& counters) const;

  // The scene's feather materials' warnings with cells (one tally each in PathCounters), and the
  // shares from the tallies summed over the render.
  const std::vector<WatchedWarning>& watched() const { return watched_; }
  std::vector<WarningShare> warning_shares(const std::vector<WarningTally>& totals) const;

 private:
  struct Vertex;
  void shade_setup(Vertex& v, const Hit& hit, V3 dir, double footprint_mm, const Spectrum4& lambda,
                   PathCounters& counters) const;
  void eval(const Vertex& v, V3 wl, Spectrum4& fcos, Spectrum4& pdf, IncidentCache& cache) const;
  bool sample(const Vertex& v, PathSampler& rng, V3& wl, Spectrum4& fcos, Spectrum4& pdf, bool& specular,
              bool& transmitted, IncidentCache& cache) const;
  void next_event(const Vertex& vx, const Spectrum4& beta, const Spectrum4& d65, double rmean, PathSampler& rng,
                  PathCounters& counters, Spectrum4& L) const;
  V3 offset_origin(V3 p, V3 ng, V3 toward) const;
  // Counts one feather BSDF evaluation at the world direction wl toward the light (the
  // material's incident direction) in the tallies of the vertex's material; observes only.
  void observe(const Vertex& v, V3 wl, const Spectrum4& beta, const Spectrum4& fcos, PathCounters& counters) const;

  const Scene& scene_;
  const Settings& settings_;
  const EmbreeScene& embree_;
  const SpectralTables& tables_;
  double eps_ = 1e-5;  // ray-origin offset, mm
  double env_pdf_ = 0.0;
  std::vector<WatchedWarning> watched_;
  std::vector<std::vector<std::size_t>> watched_of_material_;  // [material] → indices into watched_
};

}  // namespace plumage::pathtracer
