// The plug-in types core implements itself, registered with "(core)" as their library.
#include "plumage/builtin_plugins.hpp"

#include "solver/approximate_solver.hpp"

namespace plumage {

void register_validation_shape(PluginRegistry& registry);  // geometry/validation_shape.cpp

void register_builtin_plugins(PluginRegistry& registry) {
  register_validation_shape(registry);
  register_approximate_solver(registry);
}

}  // namespace plumage
