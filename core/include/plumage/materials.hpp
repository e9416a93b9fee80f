// Optical materials of feather barbules (paper Eq. 1) and their mixtures.
//
// Indices follow the time convention of conventions.hpp: n = n' + iκ, κ ≥ 0 absorbs.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "plumage/conventions.hpp"
#include "plumage/params.hpp"

namespace plumage {

class Material {
 public:
  enum class Kind { air, keratin, melanin, constant, mixture };

  // Air, n = 1.
  Material();

  static Material air();
  // Keratin, Eq. 1: n_k(λ) = 1.532 + 5890/λ² (λ in nm; non-absorbing).
  static Material keratin();
  // Melanin, Eq. 1: n_m(λ) = 1.648 + 23700/λ² + i·0.56·exp(−λ/270).
  static Material melanin();
  // A dispersionless medium of constant complex index (Im n ≥ 0 required).
  static Material constant(Complex index);
  // Linear mixture of refractive indices by volume fraction of `guest`:
  // n = (1 − f)·n_host + f·n_guest (the paper's and reference code's rule; not Maxwell Garnett).
  static Material mixture(const Material& host, const Material& guest, double guest_fraction);

  Kind kind() const { return kind_; }
  Complex index(double lambda_nm) const;
  // "air", "keratin", "1.5+0.01i", "mix(air, melanin, 0.9)".
  std::string name() const;
  // For a mixture: the same mixture with another guest fraction.
  Material with_fraction(double guest_fraction) const;
  double fraction() const { return fraction_; }
  // For a mixture: its host and guest materials (the material itself otherwise).
  const Material& host() const { return parts_ ? (*parts_)[0] : *this; }
  const Material& guest() const { return parts_ ? (*parts_)[1] : *this; }

 private:
  Kind kind_ = Kind::air;
  Complex value_{1.0, 0.0};
  double fraction_ = 0.0;
  std::shared_ptr<const std::vector<Material>> parts_;  // host, guest (mixtures only)
};

// Names usable in configs and on the command line.
std::vector<std::string> material_names();

// Reads a material from a config value at `key`. Accepted forms:
//   keratin | melanin | air                       a named material
//   {n: 1.56, k: 0.01}                            constant index n + ik
//   {mix: [air, melanin], fraction: 0.9}          linear mixture, fraction of the second
Material parse_material(const ParamView& parent, std::string_view key);
Material parse_material(const ParamView& node);

// Command-line form: a name, a number "1.5", a complex "1.5+0.01i", or "mix(air,melanin,0.9)".
// Throws std::invalid_argument with a message that names the problem.
Material parse_material_text(std::string_view text);

}  // namespace plumage
