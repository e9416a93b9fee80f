// Python bindings: simulate (issue 24; being written).
#include "py_common.hpp"

namespace plumage::python {

void bind_simulate(py::module_& m) { (void)m; }

}  // namespace plumage::python
