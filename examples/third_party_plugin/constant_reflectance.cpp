// A LocalReflection of constant, polarization-independent reflectance: the smallest useful
// plug-in, e.g. a stand-in "grey mirror" under every surface point.
//
// | name        | type   | unit | default | meaning                                   |
// |-------------|--------|------|---------|-------------------------------------------|
// | reflectance | number | 1    | 0.04    | power reflectance R in [0, 1], real r = √R |
#include <cmath>

#include <plumage/local_reflection.hpp>
#include <plumage/plugin_export.hpp>

namespace {

class ConstantReflectance final : public plumage::LocalReflection {
 public:
  explicit ConstantReflectance(double reflectance) : amplitude_(std::sqrt(reflectance)) {}

  void reflect(std::span<const Request> requests, std::span<plumage::JonesReflection> out) const override {
    for (std::size_t i = 0; i < requests.size(); ++i) out[i] = {amplitude_, 0.0, 0.0, amplitude_};
  }

 private:
  double amplitude_;
};

void register_constant(plumage::Registrar& registrar) {
  registrar.add<plumage::LocalReflection>(
      {.kind = "",
       .type = "constant_reflectance",
       .version = "1.0.0",
       .summary = "constant power reflectance at every point, both polarizations",
       .params = {{"reflectance", "number", "1", "0.04", "power reflectance R in [0, 1]"}}},
      [](const plumage::ParamView& params, const plumage::PluginContext&) {
        return std::make_unique<ConstantReflectance>(
            params.number_or("reflectance", 0.04, plumage::Limits::unit_interval()));
      });
}

}  // namespace

PLUMAGE_PLUGIN(register_constant)
