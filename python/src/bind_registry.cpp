// The plug-in registry from Python: plumage.Registry(plugin_path=[...]) and what it found.
#include "plumage/config_sections.hpp"
#include "py_common.hpp"

namespace plumage::python {

namespace {

py::dict param_dict(const ParamSpec& p) {
  py::dict d;
  d["name"] = p.name;
  d["type"] = p.type;
  d["unit"] = p.unit;
  d["default"] = p.default_value;
  d["range"] = p.range;
  d["condition"] = p.condition;
  d["doc"] = p.meaning;
  return d;
}

py::dict plugin_dict(const PluginRegistry::Entry& e) {
  py::dict d;
  d["kind"] = e.info.kind;
  d["type"] = e.info.type;
  d["version"] = e.info.version;
  d["summary"] = e.info.summary;
  d["library"] = e.library.empty() ? py::object(py::none()) : py::object(py::cast(e.library));
  py::list params;
  for (const auto& p : e.info.params) params.append(param_dict(p));
  d["params"] = params;
  return d;
}

}  // namespace

void bind_registry(py::module_& m) {
  py::class_<Registry, std::shared_ptr<Registry>>(m, "Registry", R"doc(
The plug-ins of a session: plumage's built-in types, then every libplumage_*.so found on the
search path — the folders of `plugin_path`, then $PLUMAGE_PLUGIN_PATH (colon-separated), then the
folder installed beside the core library — the same search as `plumage --plugin-path`.
A library that cannot be used is listed in `problems`, never raised.)doc")
      .def(py::init([](const std::vector<std::filesystem::path>& plugin_path) {
             return std::const_pointer_cast<Registry>(make_registry(plugin_path));
           }),
           py::arg("plugin_path") = std::vector<std::filesystem::path>{})
      .def_property_readonly("search_path", [](const Registry& r) { return r.search_path; },
                             "The folders scanned, in order.")
      .def("plugins",
           [](const Registry& r, const std::string& kind) {
             py::list out;
             for (const auto& e : r.registry->entries())
               if (kind.empty() || e.info.kind == kind) out.append(plugin_dict(e));
             return out;
           },
           py::arg("kind") = "",
           "Every type found (of one kind when `kind` is given): dicts of kind, type, version, "
           "summary, library (None for core's own) and params (the parameter table).")
      .def("describe",
           [](const Registry& r, const std::string& type) {
             const auto* entry = r.registry->find_any_kind(type);
             if (!entry) {
               std::vector<std::string> all;
               for (const auto& e : r.registry->entries()) all.push_back(e.info.type);
               std::string msg = "no plug-in type '" + type + "'";
               if (auto near = nearest_name(type, all)) msg += " (did you mean '" + *near + "'?)";
               throw py::key_error(msg);
             }
             return plugin_dict(*entry);
           },
           py::arg("type"), "One type's dict (as in plugins()); KeyError naming the nearest type.")
      .def_property_readonly("problems",
                             [](const Registry& r) {
                               py::list out;
                               for (const auto& p : r.registry->problems()) out.append(p.message);
                               return out;
                             },
                             "One message per library that could not be used.")
      .def("parameters_markdown", [](const Registry& r) { return parameters_markdown(*r.registry); },
           "Every config section and plug-in type as markdown (`plumage plugins describe --markdown`).");
  m.def("default_registry", [] { return std::const_pointer_cast<Registry>(registry_or_default(py::none())); },
        "The registry used when a call's `registry` is None (made on first use).");
}

}  // namespace plumage::python
