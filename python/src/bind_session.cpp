// Process-wide settings of the library from Python: the memory limit every estimate is checked
// against (`plumage --max-memory`) and the sink of long steps' progress (the command prints it on
// stderr; from Python it goes to a callable, or nowhere).
#include "plumage/data_paths.hpp"
#include "plumage/diagnostics.hpp"
#include "plumage/memory_budget.hpp"
#include "plumage/version.hpp"
#include "py_common.hpp"

#include <iostream>

namespace plumage::python {

void bind_session(py::module_& m) {
  m.def("set_max_memory",
        [](const py::object& size) {
          if (size.is_none()) return clear_memory_limit();
          const std::string text = py::str(size);
          std::uint64_t bytes = 0;
          try {
            bytes = parse_memory_size(text);
          } catch (const std::invalid_argument& e) {
            throw py::value_error(std::string("max_memory: ") + e.what());
          }
          set_memory_limit(bytes, "plumage.set_max_memory(" + text + ")");
        },
        py::arg("size"),
        "Bound the whole process's memory (e.g. '8G', '512M', or bytes); None: the machine's "
        "available memory. A computation whose estimate does not fit raises MemoryBudgetError "
        "before it starts.");
  m.def("set_step_progress",
        [](const py::object& callable) {
          if (callable.is_none()) return set_step_progress_sink({});
          auto held = std::shared_ptr<py::object>(new py::object(callable), [](py::object* o) {
            py::gil_scoped_acquire gil;
            delete o;
          });
          set_step_progress_sink([held](std::string_view step, double done, double total, std::string_view detail) {
            py::gil_scoped_acquire gil;
            (*held)(std::string(step), done, total, std::string(detail));
          });
        },
        py::arg("callable"),
        "callable(step, done, total, detail) for the long steps inside a computation (a BEM "
        "factorisation, a table build); total 0 marks a status line. None: silent (the default).");
  m.def("set_warning_echo",
        [](bool on) { diagnostics().set_echo(on ? &std::cerr : nullptr); },
        py::arg("on"),
        "Whether the first raise of each warning code is printed on stderr (default True; the "
        "command's -q turns it off). Results carry their warnings either way (metadata, .warnings).");
  m.def("data_directory", [] { return data_directory(); }, "Where the shipped data (CIE tables, scripts) is found.");
  m.attr("__version__") = kVersionString;
}

}  // namespace plumage::python
