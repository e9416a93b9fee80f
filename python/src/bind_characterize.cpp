// Python bindings: characterize (issue 24; being written).
#include "py_common.hpp"

namespace plumage::python {

void bind_characterize(py::module_& m) { (void)m; }

}  // namespace plumage::python
