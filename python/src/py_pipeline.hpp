// What the pipeline bindings share (geometry, multilayer, simulate, compare, characterize, render,
// the species' prepare): the explicit preparation step from Python arguments, complex read-only
// views, and the Python forms of a layer stack and of a far field (one pipeline result each, used
// by more than one area).
#pragma once

#include <complex>
#include <memory>
#include <string>
#include <vector>

#include "plumage/far_field.hpp"
#include "plumage/layer_profile.hpp"
#include "plumage/local_reflection.hpp"
#include "py_common.hpp"

namespace plumage::python {

// `tables` ("build" | "preview" | "never", the command's --tables) and a progress callable as the
// library's PreparationOptions; ValueError for another `tables`.
PreparationOptions preparation_from(const std::string& tables, const py::object& progress);

// The start of a run, as the command's start: the process's warnings (diagnostics.hpp) are
// cleared, so that a result's metadata carries its own run's warnings only (a Python session
// makes many runs; the command makes one).
void begin_run();

// A read-only numpy view of complex doubles (C order) owned by `owner`: no copy.
py::array complex_view_of(const std::complex<double>* data, std::vector<py::ssize_t> shape, py::handle owner);

// A ConfigError located at a request argument, as the library locates its own at the command's
// flag (file = "--theta-deg", no line): the same exception from Python and from the command.
[[noreturn]] void refuse_argument(const std::string& flag, const std::string& message);

// The fields of one far field as a new complex array (pol, direction, 3) (copied: the two
// polarizations are separate C++ vectors).
py::array_t<std::complex<double>> far_field_fields(const FarField& field);

// plumage.LayerProfile (bind_multilayer.cpp registers it; cross sections return it).
void bind_layer_profile(py::module_& m);

}  // namespace plumage::python
