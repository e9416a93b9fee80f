// What every binding file of the Python package shares: the registry a Python object was made
// with, numpy conversions, Python callables as progress sinks, and the declarations of the
// per-area binding functions (module.cpp calls them in order).
#pragma once

#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "plumage/plugin_registry.hpp"
#include "plumage/species_config.hpp"

namespace plumage::python {

namespace py = pybind11;

// The plug-in registry of a Python session. Every object that holds plug-in instances (a
// species, a scene, a material) keeps its registry alive: the plug-ins' code lives in the
// libraries the registry loaded, which must outlive the objects made from them.
struct Registry {
  std::shared_ptr<PluginRegistry> registry;
  std::vector<std::filesystem::path> search_path;  // the folders scanned, in order
};
using RegistryPtr = std::shared_ptr<const Registry>;

// The built-in types, then the plug-ins of PluginRegistry::search_path(plugin_path) — the
// command's search: explicit folders, $PLUMAGE_PLUGIN_PATH, the folder beside libplumage_core.so.
RegistryPtr make_registry(const std::vector<std::filesystem::path>& plugin_path);
// A loaded species config (plumage.Species) with the registry its plug-ins came from.
struct Species {
  RegistryPtr registry;
  SpeciesConfig config;
};

// `registry=None` in a Python call: the session's default registry, made on first use.
RegistryPtr registry_or_default(const py::object& registry);

// A 1-D float64 array copied from `values`.
py::array_t<double> to_array(const std::vector<double>& values);
// A read-only numpy view of `count` doubles (or `shape`, C order) owned by `owner`: no copy; the
// view keeps `owner` alive.
py::array view_of(const double* data, std::vector<py::ssize_t> shape, py::handle owner);
// A scalar or a sequence / 1-D array of numbers as doubles; `name` is the argument (for the
// TypeError / ValueError text). Non-finite values are refused.
std::vector<double> as_doubles(const py::handle& values, std::string_view name);

// A Python callable progress(done, total, what) as a C++ progress function, callable from any
// thread (it takes the GIL). An exception raised by the callable, or a pending Ctrl-C, is
// re-thrown in C++ as py::error_already_set, which stops the computation; the pybind11 call that
// started it then re-raises it in Python. None gives an empty function (only signals polled).
using ProgressFn = std::function<void(std::size_t done, std::size_t total, std::string_view what)>;
ProgressFn progress_from_python(const py::object& callable);
// True when Python has a pending signal (Ctrl-C raises KeyboardInterrupt); takes the GIL.
bool python_interrupt_pending();

// Per-area registration (one bind_*.cpp each).
void bind_errors(py::module_& m);
void bind_registry(py::module_& m);
void bind_session(py::module_& m);
void bind_configs(py::module_& m);
void bind_geometry(py::module_& m);
void bind_multilayer(py::module_& m);
void bind_simulate(py::module_& m);
void bind_compare(py::module_& m);
void bind_characterize(py::module_& m);
void bind_material(py::module_& m);
void bind_tables(py::module_& m);
void bind_measured(py::module_& m);
void bind_render(py::module_& m);

}  // namespace plumage::python
