// Shared helpers of the binding files (py_common.hpp).
#include "py_common.hpp"

#include <cmath>
#include <mutex>

#include "plumage/builtin_plugins.hpp"

namespace plumage::python {

RegistryPtr make_registry(const std::vector<std::filesystem::path>& plugin_path) {
  auto r = std::make_shared<Registry>();
  r->registry = std::make_shared<PluginRegistry>();
  register_builtin_plugins(*r->registry);
  r->search_path = PluginRegistry::search_path(plugin_path);
  {
    // Loading runs the plug-ins' static constructors only; no Python is called.
    py::gil_scoped_release release;
    r->registry->load_search_path(r->search_path);
  }
  return r;
}

RegistryPtr registry_or_default(const py::object& registry) {
  if (!registry.is_none()) return registry.cast<RegistryPtr>();
  // Made on first use and kept for the process (never destroyed before the interpreter: objects
  // made from it may live in module globals until exit).
  static RegistryPtr* session = nullptr;
  if (!session) session = new RegistryPtr(make_registry({}));
  return *session;
}

py::array_t<double> to_array(const std::vector<double>& values) {
  py::array_t<double> out(static_cast<py::ssize_t>(values.size()));
  std::copy(values.begin(), values.end(), out.mutable_data());
  return out;
}

py::array view_of(const double* data, std::vector<py::ssize_t> shape, py::handle owner) {
  std::vector<py::ssize_t> strides(shape.size());
  py::ssize_t stride = sizeof(double);
  for (std::size_t i = shape.size(); i-- > 0;) {
    strides[i] = stride;
    stride *= shape[i];
  }
  py::array out(py::dtype::of<double>(), std::move(shape), std::move(strides), data, owner);
  // It aliases C++ internals: writing through it would change a result behind the library's back.
  py::detail::array_proxy(out.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return out;
}

std::vector<double> as_doubles(const py::handle& values, std::string_view name) {
  py::array_t<double, py::array::c_style | py::array::forcecast> array;
  try {
    array = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(values);
  } catch (const py::error_already_set&) {
  }
  if (!array || array.ndim() > 1)
    throw py::type_error(std::string(name) + ": expected a number or a 1-D sequence of numbers");
  std::vector<double> out(array.data(), array.data() + array.size());
  for (double v : out)
    if (!std::isfinite(v)) throw py::value_error(std::string(name) + ": values must be finite");
  return out;
}

bool python_interrupt_pending() {
  py::gil_scoped_acquire gil;
  if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  return false;
}

ProgressFn progress_from_python(const py::object& callable) {
  if (callable.is_none()) {
    return [](std::size_t, std::size_t, std::string_view) { python_interrupt_pending(); };
  }
  // Shared so that the copies the library makes of the function release the callable (with the
  // GIL) only once, when the last copy goes.
  auto held = std::shared_ptr<py::object>(new py::object(callable), [](py::object* o) {
    py::gil_scoped_acquire gil;
    delete o;
  });
  return [held](std::size_t done, std::size_t total, std::string_view what) {
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    (*held)(done, total, std::string(what));
  };
}

}  // namespace plumage::python
