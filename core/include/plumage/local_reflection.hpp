// Extension point: reflection of a locally planar structure under one surface point (paper §4.2,
// §4.3). Implementations: "multilayer" (plugins/multilayer), "photonic_crystal" (table lookup).
#pragma once

#include <functional>
#include <span>
#include <string>
#include <string_view>

#include "plumage/conventions.hpp"
#include "plumage/layer_profile.hpp"
#include "plumage/plugin.hpp"

namespace plumage {

// Incidence at a surface point in that point's local frame: θ is the longitudinal angle (out of
// the cross-section plane, unchanged by the local tilt), φ_local the azimuth from the local
// outward normal. The 3D angle α to the normal obeys cos α = cos θ · cos φ_local.
struct LocalIncidence {
  double theta_rad = 0.0;
  double phi_local_rad = 0.0;

  double cos_alpha() const { return std::cos(theta_rad) * std::cos(phi_local_rad); }
};

// Reflection of the specular order as a Jones matrix in the (s, p) basis of the incidence plane:
// amplitudes a_s = E·ŝ and a_p = η0·H·ŝ with ŝ = ω_i × n̂ / |ω_i × n̂| (both in V/m), referenced
// to the top interface at the surface point, so that reflected = R · incident.
// A multilayer has ss = Γ_s (E-field Fresnel-type coefficient), pp = Γ_p (H-field coefficient),
// and no cross terms; a photonic crystal may couple s and p at conical incidence.
struct JonesReflection {
  Complex ss{0.0, 0.0};
  Complex sp{0.0, 0.0};  // reflected s from incident p
  Complex ps{0.0, 0.0};  // reflected p from incident s
  Complex pp{0.0, 0.0};
};

// Power reflected, into both polarizations, of s- and of p-incident light: R_s = |r_ss|² + |r_ps|²,
// R_p = |r_pp|² + |r_sp|² (what `plumage table query` and ReflectionTable.reflectance report).
inline double reflectance_s(const JonesReflection& r) { return std::norm(r.ss) + std::norm(r.ps); }
inline double reflectance_p(const JonesReflection& r) { return std::norm(r.pp) + std::norm(r.sp); }

// How the explicit preparation step (issue 22: no hidden heavy work) may satisfy a model's
// one-time needs, such as a photonic crystal's reflection table.
struct PreparationOptions {
  // build: as configured; preview: a small preview-fidelity table instead of a larger one (a test
  // shortcut: the model raises a warning, so every file made with it says so); never: refuse.
  enum class Tables { build, preview, never };
  Tables tables = Tables::build;
  // (work done, total work, what); total 0: a status line (what is about to be done). May be empty.
  std::function<void(std::size_t done, std::size_t total, std::string_view what)> progress;
};

class LocalReflection : public PluginObject {
 public:
  static constexpr std::string_view plugin_kind = "local_reflection";

  // The heavy one-time work prepare() would do, in one line ("" when there is none or it is
  // done), e.g. "build the reflection table of mallard-green (50 x 20 x 50 entries)". Creating a
  // model never does such work; reflect() of a model that needs preparation throws.
  virtual std::string pending_preparation() const { return {}; }
  // Does that work (idempotent; not concurrently with reflect()). Throws Error when the options
  // refuse it (Tables::never) or it fails.
  virtual void prepare(const PreparationOptions& options) const {}

  struct Request {
    double lambda_nm = 550.0;
    LocalIncidence incidence;
    const LayerProfile* profile = nullptr;  // the stack under the point (may be unused)
  };

  // Batch evaluation: out[i] answers requests[i]. Implementations may exploit runs of requests
  // that share a wavelength or a profile.
  virtual void reflect(std::span<const Request> requests,
                       std::span<JonesReflection> out) const = 0;

  JonesReflection reflect_one(const Request& request) const {
    JonesReflection r;
    reflect(std::span<const Request>(&request, 1), std::span<JonesReflection>(&r, 1));
    return r;
  }
};

}  // namespace plumage
