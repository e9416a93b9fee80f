// plumage.Material from Python: a feather material (.plm, feather_material.hpp) and what
// `plumage brdf plot|check` computes of it (brdf_report.hpp): the hemisphere panels of paper
// Fig. 10 and the white furnace. The BSDF itself is bind_bsdf.cpp.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "plumage/atomic_file.hpp"
#include "plumage/brdf_report.hpp"
#include "plumage/colour.hpp"
#include "py_material.hpp"

namespace plumage::python {

MaterialPtr load_material(const std::filesystem::path& file) {
  auto m = std::make_shared<Material>();
  m->file = file;
  py::gil_scoped_release release;
  m->data = std::make_shared<const FeatherMaterial>(read_feather_material(file));
  return m;
}

namespace {

// `plumage brdf plot --incident "θ,φ ..."` as a sequence of (theta_deg, phi_deg) pairs; the ranges
// are the library's (check_hemisphere_plot_options, ConfigError at the command's flag).
HemispherePlotOptions plot_options(const py::handle& incidents, int instances, int size, double exposure) {
  HemispherePlotOptions o;
  for (const py::handle item : incidents) {
    const auto pair = py::cast<std::vector<double>>(item);
    if (pair.size() != 2) throw py::value_error("incidents: each entry is (theta_deg, phi_deg)");
    o.incidents.push_back({pair[0], pair[1]});
  }
  o.instances = instances;
  o.size = size;
  o.exposure = exposure;
  check_hemisphere_plot_options(o);
  return o;
}

// Panels as arrays: XYZ (rows, columns, size, size, 3), NaN outside the disk, and the picture's
// display sRGB (to_srgb8 of XYZ × exposure, as the command's figure; 0 outside the disk).
py::dict panels_dict(const HemispherePanels& p) {
  const auto size = static_cast<py::ssize_t>(p.size);
  py::array_t<double> xyz({static_cast<py::ssize_t>(p.rows), static_cast<py::ssize_t>(p.columns), size, size, py::ssize_t{3}});
  py::array_t<std::uint8_t> rgb({static_cast<py::ssize_t>(p.rows), static_cast<py::ssize_t>(p.columns), size, size, py::ssize_t{3}});
  double* x = xyz.mutable_data();
  std::uint8_t* c = rgb.mutable_data();
  for (const std::vector<Xyz>& panel : p.xyz) {
    for (const Xyz& v : panel) {
      *x++ = v.x, *x++ = v.y, *x++ = v.z;
      const bool inside = !std::isnan(v.x);
      const Rgb8 s = inside ? to_srgb8(Xyz{v.x * p.exposure, v.y * p.exposure, v.z * p.exposure}) : Rgb8{};
      *c++ = s.r, *c++ = s.g, *c++ = s.b;
    }
  }
  py::dict d;
  d["xyz"] = xyz;
  d["srgb8"] = rgb;
  d["exposure"] = p.exposure;
  d["automatic_exposure"] = p.automatic_exposure;
  return d;
}

py::dict furnace_dict(const FurnaceReport& r) {
  const std::size_t n = r.bins.size();
  py::array_t<double> lambda(static_cast<py::ssize_t>(n)), t(static_cast<py::ssize_t>(n)),
      worst(static_cast<py::ssize_t>(n)), raw(static_cast<py::ssize_t>(n));
  py::array_t<int> over(static_cast<py::ssize_t>(n)), cn(static_cast<py::ssize_t>(n)), cc(static_cast<py::ssize_t>(n));
  for (std::size_t w = 0; w < n; ++w) {
    const FurnaceBin& b = r.bins[w];
    lambda.mutable_data()[w] = b.lambda_nm, t.mutable_data()[w] = b.transmission;
    worst.mutable_data()[w] = b.worst_total, raw.mutable_data()[w] = b.material_raw;
    over.mutable_data()[w] = b.raw_over_one, cn.mutable_data()[w] = b.clamped_nodes, cc.mutable_data()[w] = b.clamped_centres;
  }
  py::dict bins;
  bins["lambda_nm"] = lambda, bins["transmission"] = t, bins["worst_total"] = worst, bins["material_raw"] = raw;
  bins["raw_over_one"] = over, bins["clamped_nodes"] = cn, bins["clamped_centres"] = cc;
  py::dict d;
  d["bins"] = bins;
  d["entries"] = r.entries, d["nodes_per_bin"] = r.nodes_per_bin;
  d["worst_total"] = r.worst_total, d["worst_raw"] = r.worst_raw;
  d["raw_over_one"] = r.raw_over_one, d["clamped_nodes"] = r.clamped_nodes, d["clamped_centres"] = r.clamped_centres;
  d["passes"] = r.passes();
  return d;
}

std::string label_part(const FeatherMaterial& m, bool species) {
  const auto slash = m.label.find('/');
  if (slash == std::string::npos) return species ? m.label : "";
  return species ? m.label.substr(0, slash) : m.label.substr(slash + 1);
}

// `plumage brdf plot|check` as methods of plumage.Material.
void add_report_methods(py::class_<Material, MaterialPtr>& material) {
  material
      .def("hemisphere_panels",
           [](const MaterialPtr& s, const py::object& incidents, int instances, int size, double exposure) {
             const HemispherePlotOptions o = plot_options(incidents, instances, size, exposure);
             HemispherePanels p;
             {
               py::gil_scoped_release release;
               p = hemisphere_panels(s->data, o);
             }
             return panels_dict(p);
           },
           py::arg("incidents") = std::vector<std::pair<double, double>>{{0, 0}, {0, -45}, {45, 0}},
           py::arg("instances") = 2, py::arg("size") = 192, py::arg("exposure") = 0.0,
           "Paper Fig. 10 as arrays (`plumage brdf plot`): per incident (theta_deg, phi_deg) a row of "
           "panels, the mean BRDF then instances 0 … instances−1, over the unit disk of (wo_x, wo_y); "
           "pixel = f·cos θ_o over the bins → XYZ under D65. A dict: xyz (rows, 1+instances, size, "
           "size, 3), pixel [r, c] at (wo_x, wo_y) = (2(c+0.5)/size − 1, 1 − 2(r+0.5)/size) (row 0 on top, "
           "+y), NaN outside the disk; srgb8 (same shape, uint8: XYZ × exposure → sRGB, clipped), "
           "exposure (0 asked: the 99.5th percentile of the mean panels' luminance maps to 1), "
           "automatic_exposure.")
      .def("plot_hemispheres",
           [](const MaterialPtr& s, const std::filesystem::path& out, const py::object& incidents, int instances, int size,
              double exposure) {
             const HemispherePlotOptions o = plot_options(incidents, instances, size, exposure);
             // The command's checks of --out: not a symlink, not the material itself.
             check_output_path(out, "out");
             check_output_not_input(out, "out", s->file, "material");
             py::gil_scoped_release release;
             const HemispherePanels p = hemisphere_panels(s->data, o);
             write_hemisphere_figure(p, o, *s->data, out);
             return p.exposure;
           },
           py::arg("out"), py::arg("incidents") = std::vector<std::pair<double, double>>{{0, 0}, {0, -45}, {45, 0}},
           py::arg("instances") = 2, py::arg("size") = 192, py::arg("exposure") = 0.0,
           "`plumage brdf plot FILE --out PNG`: the same panels as one titled figure, written "
           "atomically (the same bytes as the command). Returns the exposure used. OutputPathError "
           "for a symlink or the material's own file as `out`.")
      .def("white_furnace",
           [](const MaterialPtr& s, double transmission) {
             if (!(transmission >= 0.0 && transmission <= 1.0)) throw py::value_error("transmission must be in [0, 1]");
             FurnaceReport r;
             {
               py::gil_scoped_release release;
               r = white_furnace(s->data, transmission);
             }
             return furnace_dict(r);
           },
           py::arg("transmission") = FeatherBsdfOptions{}.transmission_albedo,
           "`plumage brdf check FILE --transmission T`: A_r + T ≤ 1 at every table entry and cell "
           "centre of the BSDF built with transmission albedo T. A dict: bins (lambda_nm, "
           "transmission, worst_total, material_raw, raw_over_one, clamped_nodes, clamped_centres: "
           "arrays per bin), entries, nodes_per_bin, worst_total, worst_raw, raw_over_one, "
           "clamped_nodes, clamped_centres, passes (the command exits 1 when False; this returns).");
}

}  // namespace

void bind_material(py::module_& m) {
  py::class_<Material, MaterialPtr> material(m, "Material", R"doc(
A feather material (.plm, docs/formats.md): per wavelength bin and incident node (cos θ_i,
cos φ_i) = (i, j)/grid the eight fitted lobe parameters, and the noise pool of the BRDF
instances (paper §5, §7.1). Made by plumage.load_material or plumage.characterize.)doc");
  material.def_property_readonly("file", [](const Material& s) { return s.file; }, "The .plm it was read from.")
      .def_property_readonly("label", [](const Material& s) { return s.data->label; }, "'species/variant'.")
      .def_property_readonly("species", [](const Material& s) { return label_part(*s.data, true); })
      .def_property_readonly("variant", [](const Material& s) { return label_part(*s.data, false); })
      .def_property_readonly("fidelity", [](const Material& s) { return s.data->fidelity; })
      .def_property_readonly("config_hash", [](const Material& s) { return s.data->config_hash; },
                             "Hash of the species file's bytes it was characterised from (informative).")
      .def_property_readonly("key", [](const Material& s) { return s.data->key; },
                             "Digest of key_text: what a material store looks it up by ('' if made another way).")
      .def_property_readonly("key_text", [](const Material& s) { return s.data->key_text; },
                             "Everything its numbers depend on, one part per line.")
      .def_property_readonly("warnings", [](const Material& s) { return s.data->warnings; },
                             "The producing run's warnings, one per line ('' if none).")
      .def_property_readonly("grid", [](const Material& s) { return s.data->grid; },
                             "Incident nodes per axis minus one: cos θ_i, cos φ_i = 0 … grid over grid.")
      .def_property_readonly("lambda_nm",
                             [](const py::object& self) {
                               const auto& l = self.cast<const Material&>().data->lambda_nm;
                               return view_of(l.data(), {static_cast<py::ssize_t>(l.size())}, self);
                             },
                             "Wavelength bin starts in nm (read-only view); bin w covers [lambda_nm[w], lambda_nm[w] + bin_width_nm).")
      .def_property_readonly("bin_width_nm", [](const Material& s) { return s.data->bin_width_nm; })
      .def_property_readonly("sigma", [](const Material& s) { return s.data->sigma; }, "D_y spread of both lobes.")
      .def_property_readonly("l0", [](const Material& s) { return s.data->l0; },
                             "Correlation length at the reference unit (400 nm, normal incidence), direction cosine.")
      .def_property_readonly("noise_functions", [](const Material& s) { return s.data->noise.count(); },
                             "Functions in the noise pool (instance k uses 2k and 2k+1 modulo this).")
      .def("parameters",
           [](const Material& s, const std::string& name) {
             std::size_t f = 0;
             while (f < kMaterialParameters && name != kMaterialFieldNames[f]) ++f;
             if (f == kMaterialParameters) throw py::value_error("no material parameter '" + name + "'");
             const FeatherMaterial& d = *s.data;
             const auto g = static_cast<py::ssize_t>(d.grid + 1);
             py::array_t<double> out({static_cast<py::ssize_t>(d.lambda_nm.size()), g, g});
             for (std::size_t k = 0; k < d.nodes.size(); ++k) out.mutable_data()[k] = d.nodes[k].*kMaterialFields[f];
             return out;
           },
           py::arg("name"),
           "One fitted parameter at every node, shape (bins, grid+1, grid+1) indexed [w, i, j] "
           "(cos θ_i = i/grid, cos φ_i = j/grid): m_eff, phi_eff, f_eff, m_sta, phi_sta, f_sta, "
           "pol_share or correlation (feather_material.hpp).")
      .def("bsdf",
           [](const MaterialPtr& s, double transmission_albedo, int albedo_strata, double albedo_margin) {
             if (!(transmission_albedo >= 0.0 && transmission_albedo <= 1.0))
               throw py::value_error("transmission_albedo must be in [0, 1]");
             if (albedo_strata < 0) throw py::value_error("albedo_strata must be >= 0");
             auto b = std::make_shared<Bsdf>();
             b->material = s;
             FeatherBsdfOptions o;
             o.transmission_albedo = transmission_albedo;
             o.albedo_strata = albedo_strata;
             o.albedo_margin = albedo_margin;
             py::gil_scoped_release release;  // the energy budget integrates every table entry
             b->bsdf = std::make_shared<const FeatherBsdf>(s->data, o);
             return b;
           },
           py::arg("transmission_albedo") = FeatherBsdfOptions{}.transmission_albedo,
           py::arg("albedo_strata") = FeatherBsdfOptions{}.albedo_strata,
           py::arg("albedo_margin") = FeatherBsdfOptions{}.albedo_margin,
           "The BSDF (plumage.Bsdf) a renderer sees: requested diffuse transmission albedo, the "
           "energy budget's Gauss–Legendre strata (0: no budget, no transmission) and margin.")
      .def("__repr__", [](const Material& s) {
        return "<plumage.Material " + s.data->label + " (" + s.data->fidelity + ", " +
               std::to_string(s.data->lambda_nm.size()) + " bins, grid " + std::to_string(s.data->grid) + ")>";
      });

  add_report_methods(material);

  m.def("load_material", &load_material, py::arg("file"),
        "Read a feather material (.plm); InputFileError for a missing, damaged or foreign file.");
  bind_bsdf(m);
}

}  // namespace plumage::python
