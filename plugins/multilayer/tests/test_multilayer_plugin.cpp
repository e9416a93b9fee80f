// The "multilayer" plug-in loaded through the registry answers exactly like the numerics.
#include <catch2/catch.hpp>

#include "plumage/local_reflection.hpp"
#include "plumage/plugin_registry.hpp"
#include "stack_solver.hpp"

using namespace plumage;

TEST_CASE("multilayer plug-in loads and matches the stack solver", "[multilayer][plugin]") {
  PluginRegistry registry;
  registry.load_library(std::filesystem::path(PLUMAGE_TEST_PLUGIN_DIR) / "libplumage_multilayer.so");
  auto model = registry.create_named<LocalReflection>("multilayer", ParamView{}, registry.context());

  LayerProfile stack;
  stack.layers = {{Material::keratin(), 300.0}, {Material::melanin(), 120.0},
                  {Material::mixture(Material::air(), Material::melanin(), 0.9), 500.0}};
  std::vector<LocalReflection::Request> requests;
  for (double lambda : {400.0, 550.0, 700.0}) {
    for (double theta : {0.0, 0.3}) {
      for (double phi : {0.0, 0.5, 1.2}) requests.push_back({lambda, {theta, phi}, &stack});
    }
  }
  std::vector<JonesReflection> out(requests.size());
  model->reflect(requests, out);
  for (std::size_t i = 0; i < requests.size(); ++i) {
    const auto& q = requests[i];
    std::vector<Complex> index{1.0, Material::keratin().index(q.lambda_nm),
                               Material::melanin().index(q.lambda_nm),
                               stack.layers[2].material.index(q.lambda_nm), 1.0};
    std::vector<double> thick{300.0, 120.0, 500.0};
    const double c = q.incidence.cos_alpha();
    const auto r = multilayer::reflect_stack(index, thick, q.lambda_nm, 1.0 - c * c);
    // Runs of four go through the vectorised lanes: equal to rounding, not bit for bit.
    CHECK(std::abs(out[i].ss - r.r_s) < 1e-13);
    CHECK(std::abs(out[i].pp - r.r_p) < 1e-13);
    CHECK(out[i].sp == Complex(0.0, 0.0));
    CHECK(out[i].ps == Complex(0.0, 0.0));
  }
  // A request without a profile is refused, not dereferenced.
  LocalReflection::Request bad{550.0, {}, nullptr};
  CHECK_THROWS_WITH(model->reflect_one(bad), Catch::Contains("no layer profile"));
}
