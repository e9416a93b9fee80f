// Measured reflectance spectra from Python (issue 25): the reader of `plumage spectra --measured`
// and the comparison it prints (peak positions, RMS error, correlation).
#include "plumage/measured_spectrum.hpp"
#include "py_common.hpp"

namespace plumage::python {

namespace {

py::dict curve_dict(const MeasuredCurve& c) {
  py::dict d;
  d["label"] = c.label;
  d["theta_deg"] = c.theta_deg ? py::cast(*c.theta_deg) : py::none();
  d["lambda_nm"] = to_array(c.lambda_nm);
  d["reflectance"] = to_array(c.reflectance);
  return d;
}

MeasuredCurve curve_from(const py::dict& d) {
  MeasuredCurve c;
  c.label = d.contains("label") ? py::str(d["label"]).cast<std::string>() : "measured";
  if (d.contains("theta_deg") && !d["theta_deg"].is_none()) c.theta_deg = d["theta_deg"].cast<double>();
  if (!d.contains("lambda_nm") || !d.contains("reflectance"))
    throw py::value_error("measured: a dict with lambda_nm and reflectance (a curve of read_measured_spectrum)");
  c.lambda_nm = as_doubles(d["lambda_nm"], "measured lambda_nm");
  c.reflectance = as_doubles(d["reflectance"], "measured reflectance");
  if (c.lambda_nm.size() != c.reflectance.size())
    throw py::value_error("measured: lambda_nm and reflectance differ in length");
  return c;
}

}  // namespace

void bind_measured(py::module_& m) {
  m.def("read_measured_spectrum",
        [](const std::filesystem::path& file, const py::object& column) {
          MeasuredSpectrumOptions options;
          if (!column.is_none()) options.sample_column = column.cast<std::size_t>();
          MeasuredSpectrum s;
          {
            py::gil_scoped_release release;
            s = read_measured_spectrum(file, options);
          }
          py::dict d;
          d["file"] = s.file;
          py::list curves;
          for (const auto& c : s.curves) curves.append(curve_dict(c));
          d["curves"] = curves;
          d["notes"] = s.notes;
          return d;
        },
        py::arg("file"), py::arg("column") = py::none(),
        "`plumage spectra --measured FILE` 's reader: CSV/TSV/spectrometer text (header lines, "
        "',' ';' tab or blanks, decimal comma, percent or fraction, nm or um, angle columns). "
        "A dict: file, curves (each label, theta_deg or None, lambda_nm, reflectance as a "
        "fraction), notes (what the reader decided). `column`: which sample of several "
        "(--measured-column). InputFileError naming file:line for a bad file.");
  m.def("compare_spectra",
        [](const py::handle& lambda_nm, const py::handle& reflectance, const py::dict& measured) {
          const std::vector<double> l = as_doubles(lambda_nm, "lambda_nm");
          const std::vector<double> r = as_doubles(reflectance, "reflectance");
          if (l.size() != r.size()) throw py::value_error("lambda_nm and reflectance differ in length");
          const SpectrumComparison c = compare_spectra(l, r, curve_from(measured));
          py::dict d;
          d["predicted_peak_nm"] = c.predicted_peak_nm;
          d["measured_peak_nm"] = c.measured_peak_nm;
          d["peak_difference_nm"] = c.peak_difference_nm;
          d["rms_error"] = c.rms_error;
          d["correlation"] = c.correlation;
          d["common_nm"] = py::make_tuple(c.common_from_nm, c.common_to_nm);
          d["points"] = c.points;
          return d;
        },
        py::arg("lambda_nm"), py::arg("reflectance"), py::arg("measured"),
        "A predicted spectrum (strictly increasing lambda_nm, reflectance as a fraction) against a "
        "measured curve (a dict of read_measured_spectrum's curves): parabolic peak positions and "
        "their difference (measured - predicted, nm), RMS error and correlation over the predicted "
        "wavelengths inside the common range (the measurement interpolated linearly onto them).");
}

}  // namespace plumage::python
