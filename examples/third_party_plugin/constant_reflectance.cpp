// A LocalReflection of constant, polarization-independent reflectance: the smallest useful
// plug-in, e.g. a stand-in "grey mirror" under every surface point. Its one parameter is declared
// once, in a ParamTable: that declaration reads it, checks its range and documents it
// (`plumage plugins describe constant_reflectance`).
#include <cmath>

#include <plumage/local_reflection.hpp>
#include <plumage/param_table.hpp>
#include <plumage/plugin_export.hpp>

namespace {

struct ConstantParams {
  double reflectance = 0.04;
};

const plumage::ParamTable<ConstantParams>& constant_table() {
  static const auto table = plumage::ParamTable<ConstantParams>{}.number(
      "reflectance", &ConstantParams::reflectance, "1", 0.04, plumage::Limits::unit_interval(),
      "power reflectance R (real amplitude r = sqrt R, both polarizations)");
  return table;
}

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
      {.type = "constant_reflectance",
       .version = "1.0.0",
       .summary = "constant power reflectance at every point, both polarizations",
       .params = constant_table().specs()},
      [](const plumage::ParamView& params, const plumage::PluginContext&) {
        return std::make_unique<ConstantReflectance>(constant_table().read(params).reflectance);
      });
}

}  // namespace

PLUMAGE_PLUGIN(register_constant)
