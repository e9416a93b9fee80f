// Configuration files from Python: species (plumage.Species), and `plumage check` of any config.
#include "plumage/config_check.hpp"
#include "plumage/species_config.hpp"
#include "py_common.hpp"
#include "py_pipeline.hpp"

namespace plumage::python {

namespace {

py::dict simulation_dict(const SimulationSettings& s) {
  py::dict d;
  d["fidelity"] = s.fidelity;
  d["instances"] = s.instances;
  d["lambda_nm"] = to_array(s.wavelengths_nm);
  d["incident_grid"] = s.incident_grid;
  d["pattern_samples"] = s.pattern_samples;
  d["projected_samples"] = s.projected_samples;
  d["azimuth_jitter_deg"] = s.azimuth_jitter_deg;
  return d;
}

}  // namespace

void bind_configs(py::module_& m) {
  py::class_<Species, std::shared_ptr<Species>>(m, "Species", R"doc(
A species config (configs/species/<name>.yaml) with one colour variant merged, every plug-in it
names created. Made by plumage.load_species.)doc")
      .def_property_readonly("file", [](const Species& s) { return s.config.file; })
      .def_property_readonly("species", [](const Species& s) { return s.config.species; })
      .def_property_readonly("common_name", [](const Species& s) { return s.config.common_name; })
      .def_property_readonly("variant", [](const Species& s) { return s.config.variant; })
      .def_property_readonly("variants", [](const Species& s) { return s.config.variants; })
      .def_property_readonly("solver_type", [](const Species& s) { return s.config.solver_type; })
      .def_property_readonly("content_hash", [](const Species& s) { return s.config.content_hash; })
      .def_property_readonly("simulation", [](const Species& s) { return simulation_dict(s.config.simulation); },
                             "The `simulation:` section over its fidelity preset (a dict; lambda_nm an array).")
      .def("simulation_at",
           [](const Species& s, const std::string& fidelity) {
             return simulation_dict(simulation_settings(s.config, fidelity));
           },
           py::arg("fidelity"), "The `simulation:` section read over another preset (preview | production | reference).")
      .def_property_readonly("pending_preparation", [](const Species& s) { return pending_preparation(s.config); },
                             "What prepare() would still do, one line per model ('' for nothing).")
      .def("prepare",
           [](const Species& s, const std::string& tables, const py::object& progress) {
             const PreparationOptions options = preparation_from(tables, progress);
             py::gil_scoped_release release;
             prepare_species(s.config, options);
           },
           py::arg("tables") = "build", py::arg("progress") = py::none(),
           "The one-time work of the species' models (a crystal's reflection table built or loaded), "
           "as `plumage --tables`; progress(done, total, what). Idempotent.")
      .def("__repr__", [](const Species& s) {
        return "<plumage.Species " + s.config.species + " variant " + s.config.variant + " (" + s.config.file.string() + ")>";
      });

  m.def("load_species",
        [](const std::filesystem::path& file, const std::string& variant, const py::object& registry) {
          auto out = std::make_shared<Species>();
          out->registry = registry_or_default(registry);
          out->config = load_species_config(file, *out->registry->registry, variant);
          return out;
        },
        py::arg("file"), py::arg("variant") = "", py::arg("registry") = py::none(),
        "Load a species config and merge one variant (default: the file's). Raises ConfigError "
        "(file, line, column, field) for any bad input.");
  m.def("check_config",
        [](const std::filesystem::path& file, const py::object& registry) {
          const RegistryPtr r = registry_or_default(registry);
          const ConfigCheck check = check_config_file(file, *r->registry);
          py::dict d;
          d["kind"] = check.kind;
          d["summary"] = check.summary;
          d["to_prepare"] = check.to_prepare;
          d["errors"] = check.errors;
          return d;
        },
        py::arg("file"), py::arg("registry") = py::none(),
        "`plumage check FILE`: load any config (species, crystal, scene, comparison) as its run "
        "would, running nothing; a dict of kind, summary, to_prepare and errors (each the "
        "file:line:col: field: message text; empty when the file is ok). Never raises for bad input.");
  m.def("resolved_config",
        [](const std::filesystem::path& file, const py::object& registry) {
          return resolved_config_yaml(file, *registry_or_default(registry)->registry);
        },
        py::arg("file"), py::arg("registry") = py::none(),
        "`plumage check --resolved FILE`: the config as the commands see it, defaults filled in (YAML text).");
}

}  // namespace plumage::python
