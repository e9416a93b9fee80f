// Barbule cross sections from Python (`plumage geometry`, core/cli/cmd_geometry.cpp): instance n
// of a species, checked for validity (instance_geometry.hpp), as arrays; its files; statistics.
#include "plumage/error.hpp"
#include "plumage/instance_geometry.hpp"
#include "py_pipeline.hpp"

namespace plumage::python {

namespace {

// Vec2 is two doubles (x, z): a polyline is an (n, 2) array of them, viewed without a copy.
static_assert(sizeof(Vec2) == 2 * sizeof(double) && std::is_standard_layout_v<Vec2>);

struct PyCrossSection {
  CrossSection section;
  std::vector<std::string> problems;
  double generate_ms = 0.0;
};
using CrossSectionPtr = std::shared_ptr<const PyCrossSection>;

py::array points_view(const std::vector<Vec2>& points, py::handle owner) {
  return view_of(points.empty() ? nullptr : &points.front().x, {static_cast<py::ssize_t>(points.size()), 2}, owner);
}

py::list regions_of(const py::object& self) {
  const auto& cs = self.cast<const PyCrossSection&>().section;
  py::list out;
  for (const Region& r : cs.regions) {
    py::dict d;
    d["outline_nm"] = points_view(r.outline, self);
    d["material"] = r.material.name();
    d["role"] = std::string(role_name(r.role));
    d["parent"] = r.parent;
    d["layer"] = r.layer;
    d["members"] = r.members;
    d["size_nm"] = r.size_nm;
    out.append(std::move(d));
  }
  return out;
}

py::dict melanosomes_of(const CrossSection& cs) {
  const auto n = static_cast<py::ssize_t>(cs.melanosomes.size());
  py::array_t<double> center({n, py::ssize_t{2}});
  py::array_t<double> diameter(n);
  py::array_t<int> row(n);
  for (py::ssize_t i = 0; i < n; ++i) {
    const Disc& d = cs.melanosomes[static_cast<std::size_t>(i)];
    center.mutable_at(i, 0) = d.center.x;
    center.mutable_at(i, 1) = d.center.z;
    diameter.mutable_at(i) = d.diameter_nm;
    row.mutable_at(i) = d.row;
  }
  py::dict out;
  out["center_nm"] = center;
  out["diameter_nm"] = diameter;
  out["row"] = row;
  return out;
}

py::object crystal_of(const py::object& self) {
  const auto& cs = self.cast<const PyCrossSection&>().section;
  if (!cs.crystal) return py::none();
  py::dict d;
  d["crystal"] = cs.crystal->crystal;
  d["crystal_name"] = cs.crystal->crystal_name;
  d["regularity"] = view_of(cs.crystal->regularity.data(), {static_cast<py::ssize_t>(cs.crystal->regularity.size())}, self);
  return d;
}

CrossSectionPictures pictures_from(bool svg, bool png, double window_um, double pixels_per_um) {
  CrossSectionPictures p;
  p.svg = svg;
  p.png = png;
  p.window_um = window_um;
  p.pixels_per_um = pixels_per_um;
  return p;
}

CrossSectionPtr generate(const Species& species, long long instance, bool allow_invalid) {
  if (instance < 0) refuse_argument("--first", "must be >= 0");
  const StructureGenerator& generator = required_structure(species.config);
  const std::string stem = species.config.species + (species.config.variant.empty() ? "" : "-" + species.config.variant);
  auto out = std::make_shared<PyCrossSection>();
  {
    py::gil_scoped_release release;
    CheckedInstance checked = generate_checked(generator, static_cast<std::uint64_t>(instance));
    if (!allow_invalid) refuse_invalid_instance(checked, stem, static_cast<std::uint64_t>(instance));
    out->section = std::move(checked.section);
    out->problems = std::move(checked.problems);
    out->generate_ms = checked.generate_ms;
  }
  return out;
}

}  // namespace

void bind_geometry(py::module_& m) {
  py::class_<PyCrossSection, std::shared_ptr<PyCrossSection>>(m, "CrossSection", R"doc(
One procedural barbule instance in the xz-plane (x across the barbule, z the macro normal; lengths
in nm), made by plumage.cross_section. Point arrays are read-only (n, 2) views [x_nm, z_nm].)doc")
      .def_property_readonly("generator", [](const PyCrossSection& s) { return s.section.generator; })
      .def_property_readonly("label", [](const PyCrossSection& s) { return s.section.label; })
      .def_property_readonly("instance", [](const PyCrossSection& s) { return s.section.instance; })
      .def_property_readonly("seed", [](const PyCrossSection& s) { return s.section.seed; })
      .def_property_readonly("width_nm", [](const PyCrossSection& s) { return s.section.width_nm(); })
      .def_property_readonly("generate_ms", [](const PyCrossSection& s) { return s.generate_ms; },
                             "Wall time of the generator alone (ms).")
      .def_property_readonly("problems", [](const PyCrossSection& s) { return s.problems; },
                             "Geometric validity problems (list of str; empty when valid).")
      .def_property_readonly("valid", [](const PyCrossSection& s) { return s.problems.empty(); })
      .def_property_readonly("top_nm", [](const py::object& self) { return points_view(self.cast<const PyCrossSection&>().section.top, self); },
                             "The lit top surface, left to right: (n, 2) read-only array of (x_nm, z_nm).")
      .def_property_readonly("bottom_nm", [](const py::object& self) { return points_view(self.cast<const PyCrossSection&>().section.bottom, self); },
                             "The bottom surface, left to right: (n, 2) read-only array of (x_nm, z_nm).")
      .def_property_readonly("top_roughness_nm",
                             [](const py::object& self) {
                               const auto& v = self.cast<const PyCrossSection&>().section.top_roughness_nm;
                               return view_of(v.data(), {static_cast<py::ssize_t>(v.size())}, self);
                             },
                             "Random height added at each top vertex (nm; empty when the top is smooth).")
      .def_property_readonly("regions", &regions_of,
                             "The exact interior, parents first: list of dicts outline_nm ((n, 2) view, "
                             "counter-clockwise), material (name), role, parent (index, -1 for the body), "
                             "layer, members, size_nm.")
      .def_property_readonly("melanosomes", [](const PyCrossSection& s) { return melanosomes_of(s.section); },
                             "The melanosome discs: dict of center_nm (n, 2), diameter_nm (n), row (n) (copies).")
      .def_property_readonly("has_layered_model", [](const PyCrossSection& s) { return s.section.layered.has_value(); },
                             "True when the reduced model is layered (types 1-4): layer_profile works.")
      .def_property_readonly("crystal", &crystal_of,
                             "The reduced crystal model (types 5-7): dict crystal, crystal_name, regularity "
                             "(per top vertex, view); None for layered barbules.")
      .def("layer_profile", [](const PyCrossSection& s, std::size_t node) {
             if (node >= s.section.top.size()) throw py::index_error("node: beyond the top surface's vertices");
             return layer_profile_at(s.section, node);
           }, py::arg("node"),
           "The local planar stack (LayerProfile) under top vertex `node` along its normal. Raises "
           "plumage.Error without a layered model.")
      .def("layer_profiles", [](const PyCrossSection& s) {
             py::gil_scoped_release release;
             return layer_profiles(s.section);
           }, "layer_profile of every top vertex (list of LayerProfile).")
      .def("write",
           [](const PyCrossSection& s, const std::filesystem::path& base, bool svg, bool png, double window_um,
              double pixels_per_um) {
             const CrossSectionPictures pictures = pictures_from(svg, png, window_um, pixels_per_um);
             py::gil_scoped_release release;
             check_cross_section_pictures(s.section, pictures);
             write_cross_section_files(s.section, base, pictures);
           },
           py::arg("base"), py::arg("svg") = true, py::arg("png") = true, py::arg("window_um") = 0.0,
           py::arg("pixels_per_um") = 50.0,
           "Write <base>.xsec and the pictures asked for (<base>.svg, <base>.png), atomically, as "
           "`plumage geometry --out DIR` writes DIR/<species>-<variant>-<n>.*. MemoryBudgetError for a "
           "picture too large.")
      .def("__repr__", [](const PyCrossSection& s) {
        return "<plumage.CrossSection " + s.section.label + " instance " + std::to_string(s.section.instance) + ", " +
               std::to_string(s.section.top.size()) + " top vertices, " + std::to_string(s.section.regions.size()) +
               " regions" + (s.problems.empty() ? "" : ", INVALID") + ">";
      });

  m.def("cross_section", &generate, py::arg("species"), py::arg("instance") = 0, py::arg("allow_invalid") = false,
        "Instance `instance` (>= 0) of the species' structure, generated and checked as `plumage "
        "geometry --first N` does. An invalid instance raises plumage.Error listing its problems "
        "unless allow_invalid (then see .problems). ConfigError when the species has no structure.");
  m.def("geometry_statistics",
        [](const std::vector<CrossSectionPtr>& sections, const std::string& label) {
          GeometryStatistics stats;
          for (const auto& s : sections) stats.add(s->section);
          return stats.report(label, static_cast<int>(sections.size()));
        },
        py::arg("sections"), py::arg("label"),
        "The report `plumage geometry --stats` prints for these cross sections (label: <species>-<variant>).");
}

}  // namespace plumage::python
