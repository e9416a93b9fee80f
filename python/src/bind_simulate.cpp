// Far fields from Python (`plumage simulate`, core/cli/cmd_simulate.cpp; simulation.hpp): a
// species → plumage.FarFieldSet, its per-unit arrays, its files, plumage.read_far_field_set.
#include "plumage/simulation.hpp"
#include "py_pipeline.hpp"

namespace plumage::python {

namespace {

using SetPtr = std::shared_ptr<const FarFieldSet>;

// One work unit of a set; keeps the set alive (its arrays are views into it).
struct PyUnit {
  SetPtr set;
  std::size_t index = 0;
  const FarFieldUnit& unit() const { return set->units[index]; }
};

const FarField& first_instance(const FarFieldUnit& u) {
  if (u.instances.empty()) throw py::value_error("the unit has no instances");
  return u.instances.front();
}

py::array phi_o_view(const py::object& self, bool pattern) {
  const FarFieldUnit& u = self.cast<const PyUnit&>().unit();
  const std::vector<double>& phi = first_instance(u).phi_o_rad;
  const std::size_t begin = pattern ? 0 : u.pattern_count, end = pattern ? u.pattern_count : phi.size();
  return view_of(phi.data() + begin, {static_cast<py::ssize_t>(end - begin)}, self);
}

// Every instance's fields in one new array (instances, pol, directions, 3): the instances are
// separate C++ vectors, so this is a copy (field(n, pol) is the zero-copy view).
py::array_t<std::complex<double>> all_fields(const PyUnit& p) {
  const FarFieldUnit& u = p.unit();
  const auto ni = static_cast<py::ssize_t>(u.instances.size());
  const auto nd = static_cast<py::ssize_t>(u.instances.empty() ? 0 : u.instances.front().phi_o_rad.size());
  py::array_t<std::complex<double>> out({ni, py::ssize_t{2}, nd, py::ssize_t{3}});
  auto* dst = out.mutable_data();
  for (const FarField& f : u.instances)
    for (int pol = 0; pol < 2; ++pol)
      for (const auto& e : f.field[pol]) dst = std::copy(e.begin(), e.end(), dst);
  return out;
}

py::array field_view(const py::object& self, std::size_t instance, int pol) {
  const FarFieldUnit& u = self.cast<const PyUnit&>().unit();
  if (instance >= u.instances.size()) throw py::index_error("instance: beyond the unit's instances");
  if (pol != 0 && pol != 1) throw py::value_error("pol: 0 or 1");
  const auto& f = u.instances[instance].field[pol];
  static_assert(sizeof(std::array<Complex, 3>) == 3 * sizeof(Complex));
  return complex_view_of(f.empty() ? nullptr : f.front().data(), {static_cast<py::ssize_t>(f.size()), 3}, self);
}

py::array_t<double> per_instance(const FarFieldUnit& u, int what) {
  const auto ni = static_cast<py::ssize_t>(u.instances.size());
  py::array_t<double> out({ni, py::ssize_t{2}});
  for (py::ssize_t n = 0; n < ni; ++n) {
    const FarField& f = u.instances[static_cast<std::size_t>(n)];
    out.mutable_at(n, 0) = what == 0 ? f.incident_power[0] : f.incident.theta_rad;
    out.mutable_at(n, 1) = what == 0 ? f.incident_power[1] : f.incident.phi_rad;
  }
  return out;
}

void bind_unit(py::module_& m) {
  py::class_<PyUnit>(m, "FarFieldUnit", R"doc(
One work unit (λ, ω_i) of a FarFieldSet: the far fields of every instance on one φ_o list (the
first pattern_count directions are the pattern set, the rest the projected set). Arrays of
directions and fields are read-only views into the set.)doc")
      .def_property_readonly("lambda_nm", [](const PyUnit& p) { return p.unit().lambda_nm; })
      .def_property_readonly("theta_rad", [](const PyUnit& p) { return p.unit().nominal.theta_rad; },
                             "The unit's nominal incident θ_i (rad), before per-instance jitter.")
      .def_property_readonly("phi_rad", [](const PyUnit& p) { return p.unit().nominal.phi_rad; },
                             "The unit's nominal incident φ_i (rad).")
      .def_property_readonly("instances", [](const PyUnit& p) { return p.unit().instances.size(); })
      .def_property_readonly("pattern_count", [](const PyUnit& p) { return p.unit().pattern_count; })
      .def_property_readonly("phi_o_rad", [](const py::object& self) {
        const FarFieldUnit& u = self.cast<const PyUnit&>().unit();
        const auto& phi = first_instance(u).phi_o_rad;
        return view_of(phi.data(), {static_cast<py::ssize_t>(phi.size())}, self);
      }, "Every outgoing azimuth φ_o (rad), pattern then projected (view).")
      .def_property_readonly("pattern_phi_o_rad", [](const py::object& self) { return phi_o_view(self, true); },
                             "φ_o of the pattern set (rad, view).")
      .def_property_readonly("projected_phi_o_rad", [](const py::object& self) { return phi_o_view(self, false); },
                             "φ_o of the projected set (rad, view; empty for full-circle sets).")
      .def_property_readonly("fields", &all_fields,
                             "𝓔 (V m^-1/2) of every instance: complex (instances, pol, directions, 3) (x, y, z); a copy.")
      .def("field", &field_view, py::arg("instance"), py::arg("pol"),
           "𝓔 of one instance and polarization (0, 1): complex (directions, 3), a read-only view.")
      .def_property_readonly("incident_power", [](const PyUnit& p) { return per_instance(p.unit(), 0); },
                             "Φ_i per instance and pol (W per m of axis): (instances, 2).")
      .def_property_readonly("incident_rad", [](const PyUnit& p) { return per_instance(p.unit(), 1); },
                             "Each instance's (θ_i, φ_i) after jitter (rad): (instances, 2).")
      .def("mean_reflectance_density",
           [](const PyUnit& p, int pol) {
             if (pol < -1 || pol > 1) throw py::value_error("pol: 0, 1 or -1 (unpolarized mean)");
             return to_array(mean_reflectance_density(p.unit(), pol));
           },
           py::arg("pol") = -1,
           "Instance mean of the reflectance density per radian of φ_o (Eq. 10) per direction: pol 0, "
           "1, or -1 for the unpolarized mean.");
}

void bind_set(py::module_& m) {
  py::class_<FarFieldSet, std::shared_ptr<FarFieldSet>>(m, "FarFieldSet", R"doc(
The far fields of every instance of a variant per work unit (λ, ω_i), both polarizations (paper
Eqs. 8-10): the result of plumage.simulate and the content of a .ffs file.)doc")
      .def_property_readonly("metadata", [](const FarFieldSet& s) { return s.metadata; },
                             "producer, config, config_hash, species, variant, solver, warnings... (dict of str).")
      .def_property_readonly("warnings", [](const FarFieldSet& s) {
        const auto it = s.metadata.find("warnings");
        return it == s.metadata.end() ? std::string() : it->second;
      }, "The run's warnings as recorded in the metadata ('' for none).")
      .def_property_readonly("units", [](const std::shared_ptr<FarFieldSet>& s) {
        std::vector<PyUnit> out;
        for (std::size_t i = 0; i < s->units.size(); ++i) out.push_back({s, i});
        return out;
      }, "The work units (list of FarFieldUnit), λ-major as simulated.")
      .def("__len__", [](const FarFieldSet& s) { return s.units.size(); })
      .def("write", [](const FarFieldSet& s, const std::filesystem::path& file) {
        py::gil_scoped_release release;
        write_far_field_set(s, file);
      }, py::arg("file"), "Write the set as a .ffs file (atomically), as `plumage simulate --out`.")
      .def("write_pattern_csv", [](const FarFieldSet& s, const std::filesystem::path& file) {
        py::gil_scoped_release release;
        write_pattern_csv(s, file);
      }, py::arg("file"), "The instance-mean Eq. 10 patterns as CSV (`plumage simulate --csv`).")
      .def("write_scattering_width_csv", [](const FarFieldSet& s, const std::filesystem::path& file) {
        py::gil_scoped_release release;
        write_scattering_width_csv(s, file);
      }, py::arg("file"), "The 2D differential scattering width of a full-circle set as CSV (`--directions full --csv`).")
      .def("draw_cone_colours", [](const FarFieldSet& s, const std::filesystem::path& png, const std::string& title) {
        py::gil_scoped_release release;
        draw_cone_colours(s, png, title);
      }, py::arg("png"), py::arg("title") = "",
      "Fig. 7: colour along the cone at the first incident direction (`--pattern`); needs two wavelengths.")
      .def("__repr__", [](const FarFieldSet& s) {
        const auto it = s.metadata.find("species");
        return "<plumage.FarFieldSet " + (it == s.metadata.end() ? std::string("?") : it->second) + ", " +
               std::to_string(s.units.size()) + " units>";
      });
}

std::shared_ptr<FarFieldSet> simulate_species(const Species& species, const py::object& lambda_nm,
                                              const py::handle& theta_deg, const py::handle& phi_deg, int instances,
                                              const std::string& directions, const std::string& tables,
                                              const py::object& progress) {
  SimulationRequest request;
  if (!lambda_nm.is_none()) request.lambdas_nm = as_doubles(lambda_nm, "lambda_nm");
  request.theta_deg = as_doubles(theta_deg, "theta_deg");
  request.phi_deg = as_doubles(phi_deg, "phi_deg");
  request.instances = instances;
  if (directions == "full") request.directions = SimulationRequest::Directions::full_circle;
  else if (directions != "pattern") throw py::value_error("directions: 'pattern' or 'full', not '" + directions + "'");
  request.preparation = preparation_from(tables, progress);
  // The same callable sees the units: (done, total, "work units"), as the command's progress bar.
  const ProgressFn report = progress_from_python(progress);
  SimulationCallbacks callbacks;
  callbacks.started = [report](std::size_t total) { report(0, total, "work units"); };
  callbacks.progress = [report](std::size_t done, std::size_t total) { report(done, total, "work units"); };
  auto out = std::make_shared<FarFieldSet>();
  begin_run();
  py::gil_scoped_release release;
  *out = simulate(species.config, request, callbacks);
  return out;
}

}  // namespace

void bind_simulate(py::module_& m) {
  bind_unit(m);
  bind_set(m);
  m.def("simulate", &simulate_species, py::arg("species"), py::arg("lambda_nm") = py::none(),
        py::arg("theta_deg") = 0.0, py::arg("phi_deg") = 0.0, py::arg("instances") = 0,
        py::arg("directions") = "pattern", py::arg("tables") = "build", py::arg("progress") = py::none(),
        "`plumage simulate`: the far fields of every instance of `species` for each work unit (λ, "
        "ω_i), a FarFieldSet. lambda_nm None: the config's wavelengths; theta_deg in [0, 90), "
        "phi_deg in (-90, 90) (numbers or 1-D); instances 0: the config's; directions 'pattern' or "
        "'full'; tables as --tables. progress(done, total, what) after each work unit (what = 'work "
        "units') and during preparation; an exception it raises, or Ctrl-C, stops the run. "
        "ConfigError at the flag (file '--theta-deg', '--lambda-nm', ...) for a request out of range. "
        "The process's warnings are cleared first, as at a command's start: the set's metadata "
        "carries this run's warnings only.");
  m.def("read_far_field_set",
        [](const std::filesystem::path& file) {
          auto out = std::make_shared<FarFieldSet>();
          py::gil_scoped_release release;
          *out = read_far_field_set(file);
          return out;
        },
        py::arg("file"), "Read a .ffs file (plumage.Error naming the file when damaged).");
}

}  // namespace plumage::python
