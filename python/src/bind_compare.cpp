// The accuracy comparison from Python (`plumage compare`, core/cli/cmd_compare.cpp): a loaded
// comparison config (plumage.Comparison), its run over a selection (plumage.ComparisonRun: each
// method's far fields, timings and metrics against the reference as arrays) and the command's
// tables and figures.
#include "plumage/comparison.hpp"
#include "plumage/comparison_report.hpp"
#include "py_pipeline.hpp"

namespace plumage::python {

namespace {

struct PyComparison {
  RegistryPtr registry;  // the methods' solvers come from its plug-ins
  Comparison comparison;
};
using ComparisonPtr = std::shared_ptr<const PyComparison>;

struct PyComparisonRun {
  ComparisonPtr comparison;  // the selected comparison (a copy of the loaded one)
  ComparisonSegment segment;
  std::vector<MethodRun> runs;
  ComparisonMetrics metrics;
  const Comparison& c() const { return comparison->comparison; }
};

std::size_t method_index(const Comparison& c, const py::handle& method) {
  if (py::isinstance<py::int_>(method)) {
    const auto i = method.cast<std::size_t>();
    if (i >= c.methods.size()) throw py::index_error("method: beyond the comparison's methods");
    return i;
  }
  const auto name = method.cast<std::string>();
  for (std::size_t i = 0; i < c.methods.size(); ++i)
    if (c.methods[i].name == name) return i;
  throw py::key_error("method: the comparison has no method named '" + name + "'");
}

py::list methods_of(const Comparison& c) {
  py::list out;
  for (std::size_t i = 0; i < c.methods.size(); ++i) {
    const ComparisonMethod& m = c.methods[i];
    py::dict d;
    d["name"] = m.name;
    d["solver_type"] = m.solver_type;
    d["solver_options"] = m.solver_options;
    d["geometry"] = std::string(geometry_name(m.geometry));
    d["reflection"] = m.reflection_note;
    d["reference"] = i == c.reference;
    out.append(std::move(d));
  }
  return out;
}

py::dict incidents_of(const Comparison& c) {
  std::vector<double> theta, phi;
  for (const IncidentDirection& d : c.incidents) {
    theta.push_back(rad_to_deg(d.theta_rad));
    phi.push_back(rad_to_deg(d.phi_rad));
  }
  py::dict out;
  out["theta_deg"] = to_array(theta);
  out["phi_deg"] = to_array(phi);
  return out;
}

// The metrics rows as one array per column (method and incident as indices, lambda_nm the value).
py::dict metrics_of(const PyComparisonRun& r) {
  const auto n = static_cast<py::ssize_t>(r.metrics.rows.size());
  py::array_t<int> method(n), incident(n), pol(n);
  py::array_t<double> lambda(n), correlation(n), rel_l2(n), total(n), total_ref(n);
  for (py::ssize_t i = 0; i < n; ++i) {
    const ComparisonRow& row = r.metrics.rows[static_cast<std::size_t>(i)];
    method.mutable_at(i) = static_cast<int>(row.method);
    incident.mutable_at(i) = static_cast<int>(row.incident);
    pol.mutable_at(i) = row.pol;
    lambda.mutable_at(i) = r.c().lambdas[row.lambda];
    correlation.mutable_at(i) = row.metrics.correlation;
    rel_l2.mutable_at(i) = row.metrics.rel_l2;
    total.mutable_at(i) = row.metrics.total;
    total_ref.mutable_at(i) = row.metrics.total_ref;
  }
  py::dict d;
  d["method"] = method;
  d["incident"] = incident;
  d["lambda_nm"] = lambda;
  d["pol"] = pol;
  d["correlation"] = correlation;
  d["rel_l2"] = rel_l2;
  d["total"] = total;
  d["total_ref"] = total_ref;
  return d;
}

py::dict summary_of(const PyComparisonRun& r) {
  py::dict out;
  for (std::size_t i = 0; i < r.c().methods.size(); ++i) {
    const MethodSummary& s = r.metrics.summary[i];
    const MethodRun& run = r.runs[i];
    py::dict d;
    d["correlation_min"] = s.correlation_min;
    d["correlation_mean"] = s.correlation_mean;
    d["rel_l2_mean"] = s.rel_l2_mean;
    d["rel_l2_max"] = s.rel_l2_max;
    d["abs_dR_max"] = s.abs_dR_max;
    d["prepare_s"] = run.prepare_s;
    d["solve_s"] = run.solve_s;
    d["solve_s_per_lambda"] = to_array(run.solve_s_per_lambda);
    d["regions"] = run.regions;
    out[py::str(r.c().methods[i].name)] = std::move(d);
  }
  return out;
}

// U_pol(φ_o) of one method at one incident direction: (n_lambda, n_directions).
py::array_t<double> pattern_of(const PyComparisonRun& r, const py::handle& method, std::size_t incident, int pol) {
  const std::size_t mi = method_index(r.c(), method);
  if (incident >= r.c().incidents.size()) throw py::index_error("incident: beyond the comparison's incident directions");
  if (pol < 0 || pol > 2) throw py::value_error("pol: 0, 1 or 2 (unpolarised)");
  const auto& fields = r.runs[mi].results[incident];
  const auto nd = static_cast<py::ssize_t>(fields.empty() ? 0 : fields.front().phi_o_rad.size());
  py::array_t<double> out({static_cast<py::ssize_t>(fields.size()), nd});
  auto* dst = out.mutable_data();
  for (const FarField& f : fields) {
    const std::vector<double> u = polarised_density(f, pol);
    dst = std::copy(u.begin(), u.end(), dst);
  }
  return out;
}

std::shared_ptr<PyComparisonRun> run(const PyComparison& loaded, const py::object& only, const py::object& reference,
                                     const py::object& wavelengths_nm, const py::object& instance,
                                     const std::string& tables, const py::object& progress) {
  auto selected = std::make_shared<PyComparison>(loaded);  // a selection never changes the loaded one
  ComparisonSelection selection;
  if (!only.is_none()) selection.only = py::isinstance<py::str>(only) ? std::vector<std::string>{only.cast<std::string>()}
                                                                      : only.cast<std::vector<std::string>>();
  if (!reference.is_none()) selection.reference = reference.cast<std::string>();
  if (!wavelengths_nm.is_none()) selection.wavelengths_nm = as_doubles(wavelengths_nm, "wavelengths_nm");
  if (!instance.is_none()) selection.instance = instance.cast<std::int64_t>();
  const PreparationOptions preparation = preparation_from(tables, progress);
  const ProgressFn report = progress_from_python(progress);
  auto out = std::make_shared<PyComparisonRun>();
  out->comparison = selected;
  begin_run();
  py::gil_scoped_release release;
  // The command's order: select, segment, prepare, run, compare.
  select_in_comparison(selected->comparison, selection);
  out->segment = make_comparison_segment(selected->comparison);
  prepare_comparison(selected->comparison, preparation);
  out->runs = run_comparison(selected->comparison, out->segment, [&report](std::size_t done, std::size_t total, double) {
    report(done, total, "method-wavelength solves");
  });
  out->metrics = compare_methods(selected->comparison, out->runs);
  return out;
}

py::dict write_tables(const PyComparisonRun& r, const std::filesystem::path& out_dir, bool pictures) {
  ComparisonFiles files;
  std::vector<std::filesystem::path> figures;
  {
    py::gil_scoped_release release;
    files = write_comparison_tables(r.c(), r.runs, r.metrics, out_dir);
    if (pictures) draw_comparison_figures(r.c(), r.runs, files, [&figures](const std::filesystem::path& f) { figures.push_back(f); });
  }
  py::dict d;
  d["metrics"] = files.metrics;
  d["patterns"] = files.patterns;
  d["times"] = files.times;
  d["figures"] = figures;
  return d;
}

void bind_run(py::module_& m) {
  py::class_<PyComparisonRun, std::shared_ptr<PyComparisonRun>>(m, "ComparisonRun", R"doc(
A comparison run (Comparison.run): every method's far fields on the segment, wall times, and the
metrics against the reference per incident direction, wavelength and polarization.)doc")
      .def_property_readonly("name", [](const PyComparisonRun& r) { return r.c().name; })
      .def_property_readonly("methods", [](const PyComparisonRun& r) { return methods_of(r.c()); },
                             "The methods run (list of dicts), in order.")
      .def_property_readonly("reference", [](const PyComparisonRun& r) { return r.c().methods[r.c().reference].name; })
      .def_property_readonly("lambda_nm", [](const PyComparisonRun& r) { return to_array(r.c().lambdas); })
      .def_property_readonly("incidents", [](const PyComparisonRun& r) { return incidents_of(r.c()); },
                             "Incident directions: dict of theta_deg, phi_deg arrays.")
      .def_property_readonly("instance", [](const PyComparisonRun& r) { return r.c().instance; })
      .def_property_readonly("phi_o_rad", [](const PyComparisonRun& r) {
        if (r.runs.empty() || r.runs.front().results.empty() || r.runs.front().results.front().empty()) return to_array({});
        return to_array(r.runs.front().results.front().front().phi_o_rad);
      }, "The outgoing azimuths of every pattern (rad).")
      .def("pattern", &pattern_of, py::arg("method"), py::arg("incident") = 0, py::arg("pol") = 2,
           "Reflectance density per radian (Eq. 10) of `method` (name or index) at incident direction "
           "`incident`: pol 0, 1 or 2 (unpolarised); (n_lambda, n_directions).")
      .def("field", [](const PyComparisonRun& r, const py::handle& method, std::size_t incident, std::size_t lambda) {
             const auto& results = r.runs[method_index(r.c(), method)].results;
             if (incident >= results.size() || lambda >= results[incident].size()) throw py::index_error("incident or lambda index out of range");
             return far_field_fields(results[incident][lambda]);
           }, py::arg("method"), py::arg("incident"), py::arg("lambda_index"),
           "𝓔 of one method, incident direction and wavelength index: complex (pol, directions, 3), a copy.")
      .def_property_readonly("metrics", &metrics_of,
                             "The metrics rows (the metrics CSV) as a dict of 1-D arrays: method, incident "
                             "(indices), lambda_nm, pol (0, 1; 2 unpolarised), correlation, rel_l2, total, total_ref.")
      .def_property_readonly("summary", &summary_of,
                             "Per method name: the unpolarised summary (correlation_min/mean, rel_l2_mean/max, "
                             "abs_dR_max) and timings (prepare_s, solve_s, solve_s_per_lambda, regions).")
      .def("metrics_csv", [](const PyComparisonRun& r) { return comparison_metrics_csv(r.c(), r.metrics); },
           "The text of <name>-metrics.csv.")
      .def("write", &write_tables, py::arg("out_dir"), py::arg("pictures") = true,
           "Write <out_dir>/<name>-metrics.csv, -patterns.csv, -times.csv and (pictures) the figures, "
           "as `plumage compare --out`; a dict of the paths written.");
}

}  // namespace

void bind_compare(py::module_& m) {
  bind_run(m);  // first: Comparison.run's signature names it
  py::class_<PyComparison, std::shared_ptr<PyComparison>>(m, "Comparison", R"doc(
A comparison config (configs/compare/*.yaml) loaded with every method's solver created; nothing
has run. Made by plumage.load_comparison.)doc")
      .def_property_readonly("file", [](const PyComparison& c) { return c.comparison.file; })
      .def_property_readonly("name", [](const PyComparison& c) { return c.comparison.name; })
      .def_property_readonly("species", [](const PyComparison& c) {
        return std::make_shared<Species>(Species{c.registry, c.comparison.species});
      }, "The species compared (plumage.Species).")
      .def_property_readonly("segment_um", [](const PyComparison& c) { return c.comparison.segment_um; })
      .def_property_readonly("instance", [](const PyComparison& c) { return c.comparison.instance; })
      .def_property_readonly("lambda_nm", [](const PyComparison& c) { return to_array(c.comparison.lambdas); })
      .def_property_readonly("incidents", [](const PyComparison& c) { return incidents_of(c.comparison); },
                             "Incident directions: dict of theta_deg, phi_deg arrays.")
      .def_property_readonly("pattern_samples", [](const PyComparison& c) { return c.comparison.pattern_samples; })
      .def_property_readonly("methods", [](const PyComparison& c) { return methods_of(c.comparison); },
                             "The methods (list of dicts: name, solver_type, solver_options, geometry, reflection, reference).")
      .def_property_readonly("reference", [](const PyComparison& c) { return c.comparison.methods[c.comparison.reference].name; })
      .def("describe", [](const PyComparison& c) { return describe_comparison(c.comparison); })
      .def("run", &run, py::arg("only") = py::none(), py::arg("reference") = py::none(),
           py::arg("wavelengths_nm") = py::none(), py::arg("instance") = py::none(), py::arg("tables") = "build",
           py::arg("progress") = py::none(),
           "Run the comparison as `plumage compare` with --only (names; the reference always runs), "
           "--reference, --wavelengths (nm, of the config's), --instance; a ComparisonRun. A selection "
           "the config does not have is a ConfigError at its flag ('--only', ...). progress(done, total, "
           "'method-wavelength solves'); raising in it or Ctrl-C stops the run. The GIL is released.")
      .def("__repr__", [](const PyComparison& c) { return "<plumage.Comparison " + describe_comparison(c.comparison) + ">"; });

  m.def("load_comparison",
        [](const std::filesystem::path& file, const py::object& registry) {
          auto out = std::make_shared<PyComparison>();
          out->registry = registry_or_default(registry);
          out->comparison = load_comparison(file, *out->registry->registry);
          return out;
        },
        py::arg("file"), py::arg("registry") = py::none(),
        "Load and validate a comparison config, creating every method's solver (nothing runs). "
        "ConfigError (file, line, column, field) for any bad input.");
}

}  // namespace plumage::python
