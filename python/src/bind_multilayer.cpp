// Planar layer stacks from Python: plumage.LayerProfile, the reflection of a stack over arrays
// of λ and θ (`plumage multilayer`, core/cli/cmd_multilayer.cpp) and the spectra of species'
// nominal stacks (`plumage spectra`, stack_spectra.hpp).
#include "plumage/atomic_file.hpp"
#include "plumage/error.hpp"
#include "plumage/stack_spectra.hpp"
#include "py_pipeline.hpp"

namespace plumage::python {

namespace {

Material material_from(const std::string& text, const std::string& what) {
  try {
    return parse_material_text(text);
  } catch (const std::invalid_argument& e) {
    throw py::value_error(what + ": " + e.what());
  }
}

LayerProfile profile_from_text(const std::string& text) {
  try {
    return parse_stack_text(text);
  } catch (const std::invalid_argument& e) {
    refuse_argument("--stack", e.what());
  }
}

LayerProfile profile_from_arrays(const std::vector<std::string>& materials, const py::handle& thickness_nm,
                                 const std::string& ambient, const std::string& substrate) {
  const std::vector<double> t = as_doubles(thickness_nm, "thickness_nm");
  if (t.size() != materials.size()) throw py::value_error("materials and thickness_nm differ in length");
  LayerProfile p;
  p.ambient = material_from(ambient, "ambient");
  p.substrate = material_from(substrate, "substrate");
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t[i] < 0) throw py::value_error("thickness_nm: thicknesses must be >= 0");
    p.layers.push_back({material_from(materials[i], "materials[" + std::to_string(i) + "]"), t[i]});
  }
  return p;
}

// A stack argument: a LayerProfile or the command's --stack text.
LayerProfile stack_argument(const py::handle& stack) {
  if (py::isinstance<py::str>(stack)) return profile_from_text(stack.cast<std::string>());
  return stack.cast<LayerProfile>();
}

std::vector<double> thetas_argument(const py::handle& theta_deg, double limit, bool closed) {
  const std::vector<double> thetas = as_doubles(theta_deg, "theta_deg");
  for (double t : thetas) {
    if (t < 0 || t > limit || (!closed && t == limit))
      refuse_argument("--theta-deg", std::string("angles must be in [0, 90") + (closed ? "]" : ")"));
  }
  return thetas;
}

py::dict reflect_stack(const py::handle& stack, const py::handle& lambda_nm, const py::handle& theta_deg,
                       const std::string& model_type, const std::string& tables, const py::object& progress,
                       const py::object& registry) {
  const LayerProfile profile = stack_argument(stack);
  const std::vector<double> lambdas = as_doubles(lambda_nm, "lambda_nm");
  const std::vector<double> thetas = thetas_argument(theta_deg, 90.0, true);
  const RegistryPtr r = registry_or_default(registry);
  auto model = r->registry->create_named<LocalReflection>(model_type, ParamView{}, r->registry->context());
  const PreparationOptions preparation = preparation_from(tables, progress);
  // The command's request order: θ-major, then λ (rows of the result).
  std::vector<LocalReflection::Request> requests;
  for (double t : thetas) {
    for (double l : lambdas) requests.push_back({l, {0.0, deg_to_rad(t)}, &profile});
  }
  std::vector<JonesReflection> out(requests.size());
  {
    py::gil_scoped_release release;
    model->prepare(preparation);
    model->reflect(requests, out);
  }
  const auto nt = static_cast<py::ssize_t>(thetas.size()), nl = static_cast<py::ssize_t>(lambdas.size());
  py::array_t<std::complex<double>> r_s({nt, nl}), r_p({nt, nl}), r_sp({nt, nl}), r_ps({nt, nl});
  py::array_t<double> R_s({nt, nl}), R_p({nt, nl});
  for (std::size_t i = 0; i < out.size(); ++i) {
    r_s.mutable_data()[i] = out[i].ss;
    r_p.mutable_data()[i] = out[i].pp;
    r_sp.mutable_data()[i] = out[i].sp;
    r_ps.mutable_data()[i] = out[i].ps;
    R_s.mutable_data()[i] = std::norm(out[i].ss);
    R_p.mutable_data()[i] = std::norm(out[i].pp);
  }
  py::dict d;
  d["stack"] = describe(profile);
  d["lambda_nm"] = to_array(lambdas);
  d["theta_deg"] = to_array(thetas);
  d["r_s"] = r_s;
  d["r_p"] = r_p;
  d["r_sp"] = r_sp;
  d["r_ps"] = r_ps;
  d["R_s"] = R_s;
  d["R_p"] = R_p;
  return d;
}

py::list spectra(const py::handle& species, const py::handle& lambda_nm, const py::handle& theta_deg,
                 const std::string& tables, const py::object& progress, const py::object& csv, const py::object& plot) {
  std::vector<SpeciesConfig> configs;
  if (py::isinstance<Species>(species)) configs.push_back(species.cast<const Species&>().config);
  else
    for (const auto& s : species) configs.push_back(s.cast<const Species&>().config);
  const std::vector<double> lambdas = as_doubles(lambda_nm, "lambda_nm");
  const std::vector<double> thetas = thetas_argument(theta_deg, 90.0, true);
  const PreparationOptions preparation = preparation_from(tables, progress);
  // Converted with the GIL held: nothing Python is touched below.
  const auto csv_file = csv.is_none() ? std::filesystem::path() : csv.cast<std::filesystem::path>();
  const auto plot_file = plot.is_none() ? std::filesystem::path() : plot.cast<std::filesystem::path>();
  std::vector<StackSpectrum> result;
  {
    py::gil_scoped_release release;
    result = nominal_stack_spectra(configs, lambdas, thetas, preparation);
    if (result.empty()) throw Error("none of the species has a nominal_stack to draw");
    if (!csv_file.empty()) write_text_atomically(csv_file, stack_spectra_csv(result));
    if (!plot_file.empty()) draw_stack_spectra(result, plot_file);
  }
  py::list out;
  const auto nt = static_cast<py::ssize_t>(thetas.size()), nl = static_cast<py::ssize_t>(lambdas.size());
  for (const StackSpectrum& s : result) {
    py::array_t<double> R_s({nt, nl}), R_p({nt, nl});
    for (std::size_t i = 0; i < s.points.size(); ++i) {
      R_s.mutable_data()[i] = s.points[i].r_s;
      R_p.mutable_data()[i] = s.points[i].r_p;
    }
    py::dict d;
    d["species"] = s.species;
    d["variant"] = s.variant;
    d["common_name"] = s.common_name;
    d["lambda_nm"] = to_array(lambdas);
    d["theta_deg"] = to_array(thetas);
    d["R_s"] = R_s;
    d["R_p"] = R_p;
    out.append(std::move(d));
  }
  return out;
}

}  // namespace

void bind_layer_profile(py::module_& m) {
  py::class_<LayerProfile>(m, "LayerProfile", R"doc(
A planar stack: ambient medium, layers top to bottom, substrate (paper §4.2). Made from the
command's --stack text, LayerProfile("air | keratin 300 | {melanin 90 | keratin 100}*6 | air"),
or from arrays, LayerProfile(materials=[...], thickness_nm=[...], ambient="air", substrate="air");
materials are names as on the command line (keratin, melanin, air, 1.5+0.01i, mix(air,melanin,0.9)).)doc")
      .def(py::init(&profile_from_text), py::arg("stack"))
      .def(py::init(&profile_from_arrays), py::kw_only(), py::arg("materials"), py::arg("thickness_nm"),
           py::arg("ambient") = "air", py::arg("substrate") = "air")
      .def_property_readonly("ambient", [](const LayerProfile& p) { return p.ambient.name(); })
      .def_property_readonly("substrate", [](const LayerProfile& p) { return p.substrate.name(); })
      .def_property_readonly("materials", [](const LayerProfile& p) {
        std::vector<std::string> names;
        for (const Layer& l : p.layers) names.push_back(l.material.name());
        return names;
      }, "The layers' materials, top to bottom (names).")
      .def_property_readonly("thickness_nm", [](const LayerProfile& p) {
        std::vector<double> t;
        for (const Layer& l : p.layers) t.push_back(l.thickness_nm);
        return to_array(t);
      }, "The layers' thicknesses, top to bottom (nm, a copy).")
      .def_property_readonly("total_thickness_nm", &LayerProfile::total_thickness_nm)
      .def("__len__", [](const LayerProfile& p) { return p.layers.size(); })
      .def("__str__", [](const LayerProfile& p) { return describe(p); })
      .def("__repr__", [](const LayerProfile& p) { return "<plumage.LayerProfile " + describe(p) + ">"; });
}

void bind_multilayer(py::module_& m) {
  bind_layer_profile(m);
  m.def("multilayer", &reflect_stack, py::arg("stack"), py::arg("lambda_nm"), py::arg("theta_deg") = 0.0,
        py::arg("model") = "multilayer", py::arg("tables") = "build", py::arg("progress") = py::none(),
        py::arg("registry") = py::none(),
        "`plumage multilayer`: the reflection of `stack` (LayerProfile or --stack text) through the "
        "LocalReflection plug-in `model` at every lambda_nm (1-D) and theta_deg (1-D, in [0, 90]). "
        "A dict: stack (text), lambda_nm, theta_deg, complex r_s, r_p, r_sp, r_ps and R_s = |r_s|^2, "
        "R_p = |r_p|^2, each of shape (n_theta, n_lambda). ConfigError (file '--stack' or "
        "'--theta-deg') for a bad stack or angle.");
  m.def("spectra", &spectra, py::arg("species"), py::arg("lambda_nm"), py::arg("theta_deg") = std::vector<double>{0, 30, 60},
        py::arg("tables") = "build", py::arg("progress") = py::none(), py::arg("csv") = py::none(),
        py::arg("plot") = py::none(),
        "`plumage spectra`: reflectance of each species' nominal stack (a Species or a list) through "
        "its own reflection plug-in. A list of dicts (species, variant, common_name, lambda_nm, "
        "theta_deg, R_s, R_p of shape (n_theta, n_lambda)), one per species with a nominal_stack. "
        "csv: write the command's --csv table there; plot: draw its --plot PNG.");
}

}  // namespace plumage::python
