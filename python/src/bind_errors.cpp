// C++ errors as the Python exceptions of plumage/errors.py: each carries the C++ message, and a
// ConfigError its file, line, column and field.
#include "plumage/atomic_file.hpp"
#include "plumage/characterize.hpp"
#include "plumage/error.hpp"
#include "plumage/input_file.hpp"
#include "plumage/memory_budget.hpp"
#include "py_common.hpp"

namespace plumage::python {

namespace {

[[noreturn]] void raise(const char* name, const std::exception& e) {
  py::object cls = py::module_::import("plumage.errors").attr(name);
  PyErr_SetObject(cls.ptr(), py::str(e.what()).ptr());
  throw py::error_already_set();
}

}  // namespace

void bind_errors(py::module_& m) {
  py::register_exception_translator([](std::exception_ptr p) {
    if (!p) return;
    try {
      try {
        std::rethrow_exception(p);
      } catch (const ConfigError& e) {
        py::object cls = py::module_::import("plumage.errors").attr("ConfigError");
        const SourceMark& mark = e.mark();
        py::object error = cls(e.what(), mark.file, mark.line, mark.column, e.field(), e.message());
        PyErr_SetObject(cls.ptr(), error.ptr());
      } catch (const CharacterizeCancelled& e) {
        // A cancelled run (the journal kept, nothing half-written) stops as Ctrl-C does.
        PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
      } catch (const MemoryBudgetError& e) {
        raise("MemoryBudgetError", e);
      } catch (const OutputPathError& e) {
        raise("OutputPathError", e);
      } catch (const InputFileError& e) {
        raise("InputFileError", e);
      } catch (const PluginError& e) {
        raise("PluginError", e);
      } catch (const NumericalError& e) {
        raise("NumericalError", e);
      } catch (const Error& e) {
        raise("Error", e);
      }
    } catch (py::error_already_set& e) {
      // Raised above (or importing plumage.errors failed): hand it to Python as it is.
      e.restore();
    }
  });
  (void)m;
}

}  // namespace plumage::python
