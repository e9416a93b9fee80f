// Python bindings: multilayer (issue 24; being written).
#include "py_common.hpp"

namespace plumage::python {

void bind_multilayer(py::module_& m) { (void)m; }

}  // namespace plumage::python
