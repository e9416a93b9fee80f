// Python bindings: tables (issue 24; being written).
#include "py_common.hpp"

namespace plumage::python {

void bind_tables(py::module_& m) { (void)m; }

}  // namespace plumage::python
