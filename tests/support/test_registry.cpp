#include "test_registry.hpp"

#include <algorithm>
#include <filesystem>

#include "plumage/builtin_plugins.hpp"

namespace plumage::testing {

const PluginRegistry& registry() {
  static const PluginRegistry instance = [] {
    PluginRegistry r;
    register_builtin_plugins(r);  // species configs name core's solver and validation shapes
    r.load_directory(PLUMAGE_TEST_PLUGIN_DIR);
    return r;
  }();
  return instance;
}

SpeciesConfig species(const std::string& name, const std::string& variant) {
  return load_species_config(
      std::filesystem::path(PLUMAGE_SOURCE_DIR) / "configs" / "species" / (name + ".yaml"),
      registry(), variant);
}

double distance_to(const Polyline& line, Vec2 p, double reach) {
  double best = 1e300;
  auto first = std::lower_bound(line.begin(), line.end(), p.x - reach,
                                [](const Vec2& v, double x) { return v.x < x; });
  for (std::size_t i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(0, first - line.begin() - 1));
       i + 1 < line.size() && line[i].x <= p.x + reach; ++i) {
    const Vec2 a = line[i], d = line[i + 1] - line[i];
    const double t = std::clamp(dot(p - a, d) / dot(d, d), 0.0, 1.0);
    best = std::min(best, norm(p - (a + t * d)));
  }
  return best;
}

}  // namespace plumage::testing
