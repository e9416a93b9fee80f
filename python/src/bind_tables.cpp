// Photonic-crystal cells and reflection tables from Python (issue 24): load_crystal, build_table
// (`plumage table build`) and read_table (`plumage table query` over arrays), as
// core/cli/cmd_table.cpp calls plumage/crystal_cell.hpp, table_build.hpp and reflection_table.hpp.
#include <algorithm>
#include <complex>
#include <memory>
#include <optional>

#include "plumage/atomic_file.hpp"
#include "plumage/config_check.hpp"
#include "plumage/conventions.hpp"
#include "plumage/crystal_cell.hpp"
#include "plumage/reflection_table.hpp"
#include "plumage/table_build.hpp"
#include "plumage/table_builder.hpp"
#include "py_common.hpp"

namespace plumage::python {

namespace {

// The entries are exposed as one complex array [λ][cos θ][cos φ][2][2] without a copy, so the
// four Complex members must lie back to back in (ss, sp; ps, pp) order.
static_assert(sizeof(JonesReflection) == 4 * sizeof(Complex), "JonesReflection must be four packed Complex");

struct Crystal {
  std::filesystem::path file;
  CrystalCell cell;
  std::string summary;  // the `plumage check` line
};

const char* lattice_name(CrystalCell::Lattice l) { return l == CrystalCell::Lattice::hexagonal ? "hexagonal" : "rectangular"; }

// Equal-length 1-D query arguments, a length of 1 broadcast to the others.
struct QueryPoints {
  std::vector<double> lambda_nm, theta_deg, phi_deg;
  std::size_t n = 0;
};

QueryPoints query_points(const py::handle& lambda_nm, const py::handle& theta_deg, const py::handle& phi_deg) {
  QueryPoints q{as_doubles(lambda_nm, "lambda_nm"), as_doubles(theta_deg, "theta_deg"), as_doubles(phi_deg, "phi_deg")};
  q.n = std::max({q.lambda_nm.size(), q.theta_deg.size(), q.phi_deg.size()});
  for (auto* v : {&q.lambda_nm, &q.theta_deg, &q.phi_deg}) {
    if (v->size() == q.n) continue;
    if (v->size() != 1)
      throw py::value_error("lambda_nm, theta_deg and phi_deg: expected equal lengths (or length 1), got " +
                            std::to_string(q.lambda_nm.size()) + ", " + std::to_string(q.theta_deg.size()) + ", " +
                            std::to_string(q.phi_deg.size()));
    v->assign(q.n, v->front());
  }
  return q;
}

// Jones matrices at every point, as `plumage table query` computes one (degrees → radians the same way).
std::vector<JonesReflection> query_all(const ReflectionTable& t, const QueryPoints& q) {
  std::vector<JonesReflection> out(q.n);
  py::gil_scoped_release release;
  for (std::size_t k = 0; k < q.n; ++k) out[k] = t.query(q.lambda_nm[k], deg_to_rad(q.theta_deg[k]), deg_to_rad(q.phi_deg[k]));
  return out;
}

py::dict build_result_dict(const TableBuildResult& r) {
  py::dict d;
  d["crystal"] = r.crystal;
  d["n_lambda"] = r.grid.n_lambda;
  d["n_theta"] = r.grid.n_theta;
  d["n_phi"] = r.grid.n_phi;
  d["resolution_nm"] = r.resolution_nm;
  d["notes"] = r.notes;
  return d;
}

void bind_crystal(py::module_& m) {
  py::class_<Crystal, std::shared_ptr<Crystal>>(m, "Crystal", R"doc(
A photonic-crystal cell (configs/crystals/<name>.yaml, top-level `crystal:`), validated as
`plumage check` does. Lengths in nm. Made by plumage.load_crystal.)doc")
      .def_property_readonly("file", [](const Crystal& c) { return c.file; })
      .def_property_readonly("name", [](const Crystal& c) { return c.cell.name; })
      .def_property_readonly("lattice", [](const Crystal& c) { return lattice_name(c.cell.lattice); }, "'hexagonal' or 'rectangular'.")
      .def_property_readonly("a_x_nm", [](const Crystal& c) { return c.cell.a_x_nm; }, "Lattice period along the surface (nm).")
      .def_property_readonly("a_z_nm", [](const Crystal& c) { return c.cell.a_z_nm; }, "Row spacing into the depth (nm).")
      .def_property_readonly("rod_diameter_nm", [](const Crystal& c) { return c.cell.rod_diameter_nm; })
      .def_property_readonly("core_diameter_nm", [](const Crystal& c) { return c.cell.core_diameter_nm; })
      .def_property_readonly("channel_diameter_nm", [](const Crystal& c) { return c.cell.channel_diameter_nm; })
      .def_property_readonly("rows", [](const Crystal& c) { return c.cell.rows; })
      .def_property_readonly("cortex_nm", [](const Crystal& c) { return c.cell.cortex_nm; })
      .def_property_readonly("depth_nm", [](const Crystal& c) { return c.cell.depth_nm(); }, "Cortex top to the last row's bottom (nm).")
      .def_property_readonly("expected_peak_nm", [](const Crystal& c) { return c.cell.expected_peak_nm; }, "0 when not given.")
      .def_property_readonly("materials", [](const Crystal& c) {
        py::dict d;
        d["host"] = c.cell.host.name(), d["rod"] = c.cell.rod.name(), d["core"] = c.cell.core.name(), d["channel"] = c.cell.channel.name();
        return d;
      }, "Material names of host, rod, core and channel (a dict).")
      .def_property_readonly("builder_sections", [](const Crystal& c) {
        std::vector<std::string> names;
        for (const auto& [name, section] : c.cell.builder_sections) names.push_back(name);
        return names;
      }, "Table builders with their own section in the file (e.g. ['fdtd_periodic']).")
      .def_property_readonly("summary", [](const Crystal& c) { return c.summary; }, "The summary line of `plumage check FILE`.")
      .def("__repr__", [](const Crystal& c) { return "<plumage.Crystal " + c.cell.name + " (" + c.file.string() + ")>"; });

  m.def("load_crystal",
        [](const std::filesystem::path& file, const py::object& registry) {
          const RegistryPtr r = registry_or_default(registry);
          auto out = std::make_shared<Crystal>();
          out->file = file;
          {
            py::gil_scoped_release release;
            out->cell = load_crystal_cell(file);
            // Each builder's own section, read by its parameter table: a bad key is a ConfigError here.
            check_builder_sections(out->cell, *r->registry);
            out->summary = check_config_file(file, *r->registry).summary;
          }
          return out;
        },
        py::arg("file"), py::arg("registry") = py::none(),
        "Load a crystal config as `plumage check` does (its builder sections included). Raises "
        "ConfigError (file, line, column, field) for any bad input.");
}

void bind_reflection_table(py::module_& m) {
  py::class_<ReflectionTable, std::shared_ptr<ReflectionTable>>(m, "ReflectionTable", R"doc(
A photonic-crystal reflection table (.plt): per (λ, cos θ, cos φ_local) the 2×2 Jones reflection
of the specular order in the (s, p) basis. Made by plumage.read_table.)doc")
      .def_property_readonly("lambda_nm", [](py::object self) {
        const auto& g = self.cast<const ReflectionTable&>().grid().lambda_nm;
        return view_of(g.data(), {static_cast<py::ssize_t>(g.size())}, self);
      }, "Wavelength axis (nm), ascending; read-only view.")
      .def_property_readonly("cos_theta", [](py::object self) {
        const auto& g = self.cast<const ReflectionTable&>().grid().cos_theta;
        return view_of(g.data(), {static_cast<py::ssize_t>(g.size())}, self);
      }, "cos θ axis (θ the longitudinal angle), ascending in (0, 1]; read-only view.")
      .def_property_readonly("cos_phi", [](py::object self) {
        const auto& g = self.cast<const ReflectionTable&>().grid().cos_phi;
        return view_of(g.data(), {static_cast<py::ssize_t>(g.size())}, self);
      }, "cos φ_local axis, ascending in (0, 1]; read-only view.")
      .def_property_readonly("jones", [](py::object self) {
        const ReflectionTable& t = self.cast<const ReflectionTable&>();
        const auto& g = t.grid();
        const auto nl = static_cast<py::ssize_t>(g.lambda_nm.size()), nt = static_cast<py::ssize_t>(g.cos_theta.size()),
                   np = static_cast<py::ssize_t>(g.cos_phi.size());
        const py::ssize_t c = sizeof(Complex);
        py::array out(py::dtype::of<Complex>(), {nl, nt, np, py::ssize_t{2}, py::ssize_t{2}},
                      {nt * np * 4 * c, np * 4 * c, 4 * c, 2 * c, c}, t.entries().data(), self);
        py::detail::array_proxy(out.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
        return out;
      }, "The stored entries, complex128 of shape (n_lambda, n_theta, n_phi, 2, 2), [[ss, sp], [ps, pp]]; "
         "a read-only view of the table's memory.")
      .def_property_readonly("crystal", [](const ReflectionTable& t) { return t.metadata().crystal; })
      .def_property_readonly("period_nm", [](const ReflectionTable& t) { return t.metadata().period_nm; })
      .def_property_readonly("config_hash", [](const ReflectionTable& t) { return t.metadata().config_hash; })
      .def_property_readonly("resolution_nm", [](const ReflectionTable& t) { return t.metadata().resolution_nm; })
      .def_property_readonly("producer", [](const ReflectionTable& t) { return t.metadata().producer; })
      .def_property_readonly("notes", [](const ReflectionTable& t) { return t.metadata().notes; }, "Warnings of the build, one a line.")
      .def_property_readonly("content_hash", &ReflectionTable::content_hash)
      .def("query",
           [](const ReflectionTable& t, const py::handle& lambda_nm, const py::handle& theta_deg, const py::handle& phi_deg) {
             const QueryPoints q = query_points(lambda_nm, theta_deg, phi_deg);
             const std::vector<JonesReflection> j = query_all(t, q);
             py::array_t<Complex> out({static_cast<py::ssize_t>(q.n), py::ssize_t{2}, py::ssize_t{2}});
             auto o = out.mutable_unchecked<3>();
             for (std::size_t k = 0; k < q.n; ++k) {
               const auto i = static_cast<py::ssize_t>(k);
               o(i, 0, 0) = j[k].ss, o(i, 0, 1) = j[k].sp, o(i, 1, 0) = j[k].ps, o(i, 1, 1) = j[k].pp;
             }
             return out;
           },
           py::arg("lambda_nm"), py::arg("theta_deg"), py::arg("phi_deg"),
           "`plumage table query` over arrays: the interpolated Jones reflection at each (lambda_nm, "
           "theta_deg, phi_deg), numbers or 1-D arrays of equal length (length 1 broadcast); "
           "complex128 of shape (N, 2, 2), [[ss, sp], [ps, pp]]. ValueError for unequal lengths.")
      .def("reflectance",
           [](const ReflectionTable& t, const py::handle& lambda_nm, const py::handle& theta_deg, const py::handle& phi_deg) {
             const QueryPoints q = query_points(lambda_nm, theta_deg, phi_deg);
             const std::vector<JonesReflection> j = query_all(t, q);
             py::array_t<double> out({static_cast<py::ssize_t>(q.n), py::ssize_t{2}});
             auto o = out.mutable_unchecked<2>();
             for (std::size_t k = 0; k < q.n; ++k) {
               const auto i = static_cast<py::ssize_t>(k);
               o(i, 0) = reflectance_s(j[k]);
               o(i, 1) = reflectance_p(j[k]);
             }
             return out;
           },
           py::arg("lambda_nm"), py::arg("theta_deg"), py::arg("phi_deg"),
           "R_s and R_p of `plumage table query` over arrays (as query): float64 of shape (N, 2).")
      .def("__repr__", [](const ReflectionTable& t) {
        const auto& g = t.grid();
        return "<plumage.ReflectionTable " + t.metadata().crystal + " " + std::to_string(g.lambda_nm.size()) + " x " +
               std::to_string(g.cos_theta.size()) + " x " + std::to_string(g.cos_phi.size()) + ">";
      });

  m.def("read_table",
        [](const std::filesystem::path& file) {
          py::gil_scoped_release release;
          return std::make_shared<ReflectionTable>(ReflectionTable::load(file));
        },
        py::arg("file"), "Read a reflection table file (.plt). Raises plumage.errors.Error for a missing or damaged file.");
}

void bind_build_table(py::module_& m) {
  m.def("build_table",
        [](const std::filesystem::path& crystal_file, const std::filesystem::path& out, const std::string& fidelity,
           const std::string& builder, double lambda_min_nm, double lambda_max_nm, int n_lambda, int n_theta, int n_phi,
           std::optional<double> resolution_nm, std::optional<double> k_step, bool restart, const py::object& progress,
           const py::object& registry) {
          if (fidelity != "preview" && fidelity != "production")
            throw py::value_error("fidelity: expected 'preview' or 'production', not '" + fidelity + "'");
          if (n_lambda < 0 || n_theta < 0 || n_phi < 0) throw py::value_error("n_lambda, n_theta, n_phi: expected >= 0 (0: the fidelity's)");
          const RegistryPtr r = registry_or_default(registry);
          check_output_path(out, "out");
          check_output_not_input(out, "out", crystal_file, "crystal config");
          TableBuildRequest request;
          request.crystal_config = crystal_file;
          request.out = out;
          request.fidelity = fidelity;
          request.builder = builder;
          request.lambda_min_nm = lambda_min_nm, request.lambda_max_nm = lambda_max_nm;
          request.grid = {n_lambda, n_theta, n_phi};
          request.resolution_nm = resolution_nm;
          request.k_step_per_um = k_step;
          request.restart = restart;
          const ProgressFn report = progress_from_python(progress);
          TableBuildResult result;
          {
            py::gil_scoped_release release;
            result = build_table_file(request, *r->registry, report);
          }
          return build_result_dict(result);
        },
        py::arg("crystal_file"), py::arg("out"), py::arg("fidelity") = "preview", py::arg("builder") = "fdtd_periodic",
        py::arg("lambda_min_nm") = 400.0, py::arg("lambda_max_nm") = 700.0, py::arg("n_lambda") = 0, py::arg("n_theta") = 0,
        py::arg("n_phi") = 0, py::arg("resolution_nm") = py::none(), py::arg("k_step") = py::none(), py::arg("restart") = false,
        py::arg("progress") = py::none(), py::arg("registry") = py::none(),
        "`plumage table build CRYSTAL --out OUT`: build a reflection table with a table_builder "
        "plug-in and write `out` (.plt), the same bytes as the command. Counts of 0: the fidelity's "
        "grid (preview 16 x 10 x 10, production 50 x 20 x 50); resolution_nm / k_step (1/um) None: the "
        "builder's defaults. progress(done, total, what) is called as runs finish; an exception it "
        "raises, or Ctrl-C, stops the build, whose finished runs stay in out + '.partial' for a rerun "
        "(restart=True discards them). Returns a dict (crystal, n_lambda, n_theta, n_phi, "
        "resolution_nm, notes). Raises ConfigError for a bad crystal or builder setting, "
        "OutputPathError for an output that is a symlink or a folder.");
}

}  // namespace

void bind_tables(py::module_& m) {
  bind_crystal(m);
  bind_reflection_table(m);
  bind_build_table(m);
}

}  // namespace plumage::python
