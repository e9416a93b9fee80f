// Shared helpers of the pipeline bindings (py_pipeline.hpp).
#include "py_pipeline.hpp"

#include <algorithm>

#include "plumage/diagnostics.hpp"
#include "plumage/error.hpp"

namespace plumage::python {

PreparationOptions preparation_from(const std::string& tables, const py::object& progress) {
  PreparationOptions options;
  if (tables == "build") options.tables = PreparationOptions::Tables::build;
  else if (tables == "preview") options.tables = PreparationOptions::Tables::preview;
  else if (tables == "never") options.tables = PreparationOptions::Tables::never;
  else throw py::value_error("tables: expected 'build', 'preview' or 'never', not '" + tables + "'");
  options.progress = progress_from_python(progress);
  return options;
}

void begin_run() { diagnostics().clear(); }

py::array complex_view_of(const std::complex<double>* data, std::vector<py::ssize_t> shape, py::handle owner) {
  std::vector<py::ssize_t> strides(shape.size());
  py::ssize_t stride = sizeof(std::complex<double>);
  for (std::size_t i = shape.size(); i-- > 0;) {
    strides[i] = stride;
    stride *= shape[i];
  }
  py::array out(py::dtype::of<std::complex<double>>(), std::move(shape), std::move(strides), data, owner);
  // It aliases a C++ result: writing through it would change the result behind the library's back.
  py::detail::array_proxy(out.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return out;
}

void refuse_argument(const std::string& flag, const std::string& message) {
  throw ConfigError(SourceMark{flag, 0, 0}, "", message);
}

py::array_t<std::complex<double>> far_field_fields(const FarField& field) {
  const auto n = static_cast<py::ssize_t>(field.phi_o_rad.size());
  py::array_t<std::complex<double>> out({py::ssize_t{2}, n, py::ssize_t{3}});
  auto* dst = out.mutable_data();
  for (int pol = 0; pol < 2; ++pol) {
    for (const auto& e : field.field[pol]) dst = std::copy(e.begin(), e.end(), dst);
  }
  return out;
}

}  // namespace plumage::python
