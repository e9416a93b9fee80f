// The extension module `plumage._plumage` (issue 24); python/plumage/__init__.py re-exports it.
#include "py_common.hpp"

PYBIND11_MODULE(_plumage, m) {
  using namespace plumage::python;
  m.doc() = "plumage: appearance of iridescent bird feathers from their nanostructure (C++ core)";
  bind_errors(m);  // first: the translators every later binding relies on
  bind_registry(m);
  bind_session(m);
  bind_configs(m);
  bind_geometry(m);
  bind_multilayer(m);
  bind_simulate(m);
  bind_compare(m);
  bind_characterize(m);
  bind_material(m);
  bind_tables(m);
  bind_measured(m);
  bind_render(m);
}
