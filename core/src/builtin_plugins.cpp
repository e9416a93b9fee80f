// The plug-in types core implements itself, registered with "(core)" as their library.
#include "plumage/builtin_plugins.hpp"

#include "solver/approximate_solver.hpp"

namespace plumage {

void register_validation_shape(PluginRegistry& registry);     // geometry/validation_shape.cpp
void register_xsec_file(PluginRegistry& registry);            // geometry/xsec_file.cpp
void register_svg_file(PluginRegistry& registry);             // geometry/svg_file.cpp
void register_featherlab_file(PluginRegistry& registry);      // geometry/featherlab_file.cpp
void register_approximate_ladder(PluginRegistry& registry);    // solver/approximate_ladder.cpp
void register_approximate_benchmark(PluginRegistry& registry); // solver/approximate_benchmark.cpp
void register_fit_ladder(PluginRegistry& registry);            // fit/fit_ladder.cpp
void register_geometry_benchmark(PluginRegistry& registry);    // geometry/geometry_benchmark.cpp
void register_ladder_benchmark(PluginRegistry& registry);      // report/ladder_benchmark.cpp
void register_bsdf_benchmark(PluginRegistry& registry);        // bsdf/bsdf_benchmark.cpp
void register_characterize_benchmark(PluginRegistry& registry); // pipeline/characterize_benchmark.cpp

void register_builtin_plugins(PluginRegistry& registry) {
  register_validation_shape(registry);
  register_xsec_file(registry);
  register_svg_file(registry);
  register_featherlab_file(registry);
  register_approximate_solver(registry);
  register_approximate_ladder(registry);
  register_approximate_benchmark(registry);
  register_fit_ladder(registry);
  register_geometry_benchmark(registry);
  register_ladder_benchmark(registry);
  register_bsdf_benchmark(registry);
  register_characterize_benchmark(registry);
}

}  // namespace plumage
