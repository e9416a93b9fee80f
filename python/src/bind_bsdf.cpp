// plumage.Bsdf from Python: the feather BSDF (feather_bsdf.hpp) evaluated, its pdf and its
// samples on numpy batches. Every batch runs on the calling thread with the GIL released, so
// several Python threads evaluate in parallel. Directions are unit vectors in the BRDF frame
// (x across the barbule, y along it, z the macro normal; ω_i toward the light, ω_o toward the
// viewer); values are the BSDF f in sr⁻¹, not cosine-weighted (feather_bsdf.hpp).
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "py_material.hpp"

namespace plumage::python {

namespace {

using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;

// A batch of directions, (3,) (one for all) or (N, 3).
struct Directions {
  Doubles array;
  std::size_t count = 0;  // rows; 0 for a single (3,) direction
  Direction at(std::size_t k) const {
    const double* p = array.data() + (count ? 3 * k : 0);
    return {p[0], p[1], p[2]};
  }
};

Doubles ensure_doubles(const py::handle& values, const char* name) {
  Doubles a;
  try {
    a = Doubles::ensure(values);
  } catch (const py::error_already_set&) {
  }
  if (!a) throw py::type_error(std::string(name) + ": expected an array of numbers");
  return a;
}

// The library's directions are unit vectors: anything else is a caller's mistake, reported
// rather than silently evaluated.
Directions directions(const py::handle& values, const char* name) {
  Directions d{ensure_doubles(values, name)};
  if (d.array.ndim() == 1 && d.array.shape(0) == 3) d.count = 0;
  else if (d.array.ndim() == 2 && d.array.shape(1) == 3) d.count = static_cast<std::size_t>(d.array.shape(0));
  else throw py::value_error(std::string(name) + ": expected shape (3,) or (N, 3)");
  const std::size_t n = d.count ? d.count : 1;
  for (std::size_t k = 0; k < n; ++k) {
    const Direction w = d.at(k);
    const double norm2 = w.x * w.x + w.y * w.y + w.z * w.z;
    if (!(std::abs(norm2 - 1.0) <= 1e-6))
      throw py::value_error(std::string(name) + "[" + std::to_string(k) + "] is not a unit vector (|w|^2 = " +
                            std::to_string(norm2) + ")");
  }
  return d;
}

// Wavelengths in nm, a scalar or (N,), inside the material's bins [λ_0, λ_last + width).
struct Wavelengths {
  Doubles array;
  std::size_t count = 0;  // 0 for a scalar
  double at(std::size_t k) const { return array.data()[count ? k : 0]; }
};

Wavelengths wavelengths(const py::handle& values, const FeatherMaterial& m) {
  Wavelengths l{ensure_doubles(values, "lambda_nm")};
  if (l.array.ndim() == 1) l.count = static_cast<std::size_t>(l.array.shape(0));
  else if (l.array.ndim() != 0) throw py::value_error("lambda_nm: expected a number or shape (N,)");
  const double lo = m.lambda_nm.front(), hi = m.lambda_nm.back() + m.bin_width_nm;
  for (std::size_t k = 0; k < (l.count ? l.count : 1); ++k) {
    const double v = l.at(k);
    if (!(v >= lo && v < hi))
      throw py::value_error("lambda_nm = " + std::to_string(v) + " lies outside the material's bins [" +
                            std::to_string(lo) + ", " + std::to_string(hi) + ") nm");
  }
  return l;
}

// The common length of batch arguments (0 = all scalar / single: one value).
std::size_t batch_size(std::initializer_list<std::pair<std::size_t, const char*>> counts) {
  std::size_t n = 0;
  const char* first = nullptr;
  for (const auto& [c, name] : counts) {
    if (!c) continue;
    if (n && c != n)
      throw py::value_error(std::string(name) + " has " + std::to_string(c) + " rows, " + first + " " +
                            std::to_string(n));
    n = c;
    first = name;
  }
  return n ? n : 1;
}

// The looked-up incident state per sample. One ω_i for the whole batch: its geometry once and
// one Incident per wavelength bin (incident_bin(bin, incident_geometry(wi)), equal bit for bit
// to incident(λ, wi), feather_bsdf.hpp); else per sample.
class Incidents {
 public:
  Incidents(const FeatherBsdf& bsdf, const Directions& wi, const Wavelengths& lambda)
      : bsdf_(bsdf), wi_(wi), lambda_(lambda) {
    if (!wi.count) {
      geometry_ = bsdf.incident_geometry(wi.at(0));
      per_bin_.resize(bsdf.material().lambda_nm.size());
    }
  }
  const FeatherBsdf::Incident& at(std::size_t k) {
    const std::size_t bin = bsdf_.material().wavelength_bin(lambda_.at(k));
    if (wi_.count) return scratch_ = bsdf_.incident_bin(bin, wi_.at(k));
    auto& cached = per_bin_[bin];
    if (!cached) cached = bsdf_.incident_bin(bin, *geometry_);
    return *cached;
  }

 private:
  const FeatherBsdf& bsdf_;
  const Directions& wi_;
  const Wavelengths& lambda_;
  std::optional<FeatherBsdf::IncidentGeometry> geometry_;
  std::vector<std::optional<FeatherBsdf::Incident>> per_bin_;
  FeatherBsdf::Incident scratch_;
};

enum class Value { mean, instance, pdf };

py::array_t<double> evaluate(const Bsdf& b, const py::handle& wi_in, const py::handle& wo_in,
                             const py::handle& lambda_in, Value what, std::uint64_t instance) {
  const Directions wi = directions(wi_in, "wi"), wo = directions(wo_in, "wo");
  const Wavelengths lambda = wavelengths(lambda_in, b.bsdf->material());
  const std::size_t n = batch_size({{wi.count, "wi"}, {wo.count, "wo"}, {lambda.count, "lambda_nm"}});
  py::array_t<double> out(static_cast<py::ssize_t>(n));
  double* f = out.mutable_data();
  {
    py::gil_scoped_release release;
    const FeatherBsdf& bsdf = *b.bsdf;
    Incidents incidents(bsdf, wi, lambda);
    for (std::size_t k = 0; k < n; ++k) {
      const FeatherBsdf::Incident& in = incidents.at(k);
      switch (what) {
        case Value::mean: f[k] = bsdf.eval(in, wo.at(k)); break;
        case Value::instance: f[k] = bsdf.eval(in, wo.at(k), instance); break;
        case Value::pdf: f[k] = bsdf.pdf(in, wo.at(k)); break;
      }
    }
  }
  return out;
}

// The uniform numbers of sample(): the caller's, or numpy's default generator seeded with `seed`
// (n rows; n None: one per wavelength given).
py::object uniforms(const py::object& u, const py::object& seed, const py::object& n, const Wavelengths& lambda) {
  if (!u.is_none()) {
    if (!seed.is_none() || !n.is_none()) throw py::value_error("sample: give u, or seed (and n), not both");
    return u;
  }
  if (seed.is_none()) throw py::value_error("sample: give u (N, 3) or a seed");
  const py::object rows = n.is_none() ? py::cast(lambda.count ? lambda.count : 1) : n;
  return py::module_::import("numpy").attr("random").attr("default_rng")(seed).attr("random")(py::make_tuple(rows, 3));
}

py::dict sample(const Bsdf& b, const py::handle& wi_in, const py::handle& lambda_in, const py::object& u_in,
                const py::object& seed, const py::object& rows_wanted, const std::optional<std::uint64_t>& instance) {
  const Directions wi = directions(wi_in, "wi");
  const Wavelengths lambda = wavelengths(lambda_in, b.bsdf->material());
  const py::object u_given = uniforms(u_in, seed, rows_wanted, lambda);
  const Doubles u = ensure_doubles(u_given, "u");
  if (u.ndim() != 2 || u.shape(1) != 3) throw py::value_error("u: expected shape (N, 3) of uniform numbers in [0, 1)");
  const std::size_t rows = static_cast<std::size_t>(u.shape(0));
  for (std::size_t k = 0; k < 3 * rows; ++k)
    if (!(u.data()[k] >= 0.0 && u.data()[k] < 1.0)) throw py::value_error("u: values must lie in [0, 1)");
  const std::size_t n = batch_size({{wi.count, "wi"}, {lambda.count, "lambda_nm"}, {rows, "u"}});
  if (n != rows) throw py::value_error("u: needs one row per sample");
  py::array_t<double> wo({static_cast<py::ssize_t>(n), py::ssize_t{3}});
  py::array_t<double> f(static_cast<py::ssize_t>(n)), pdf(static_cast<py::ssize_t>(n)), weight(static_cast<py::ssize_t>(n));
  py::array_t<bool> transmitted(static_cast<py::ssize_t>(n));
  double *po = wo.mutable_data(), *pf = f.mutable_data(), *pp = pdf.mutable_data(), *pw = weight.mutable_data();
  bool* pt = transmitted.mutable_data();
  {
    py::gil_scoped_release release;
    const FeatherBsdf& bsdf = *b.bsdf;
    Incidents incidents(bsdf, wi, lambda);
    const double* pu = u.data();
    for (std::size_t k = 0; k < n; ++k) {
      const FeatherBsdf::Incident& in = incidents.at(k);
      const BsdfSample s = instance ? bsdf.sample(in, pu[3 * k], pu[3 * k + 1], pu[3 * k + 2], *instance)
                                    : bsdf.sample(in, pu[3 * k], pu[3 * k + 1], pu[3 * k + 2]);
      po[3 * k] = s.wo.x, po[3 * k + 1] = s.wo.y, po[3 * k + 2] = s.wo.z;
      pf[k] = s.f, pp[k] = s.pdf, pw[k] = s.weight, pt[k] = s.transmitted;
    }
  }
  py::dict d;
  d["wo"] = wo, d["f"] = f, d["pdf"] = pdf, d["weight"] = weight, d["transmitted"] = transmitted;
  if (u_in.is_none()) d["u"] = u_given;  // the numbers drawn from the seed
  return d;
}

}  // namespace

void bind_bsdf(py::module_& m) {
  py::class_<Bsdf, std::shared_ptr<Bsdf>>(m, "Bsdf", R"doc(
The feather BSDF of a material (feather_bsdf.hpp; paper §5.2–5.3, §7.1–7.2): the mean BRDF f̄
(Eq. 16), BRDF instance k (Eq. 22) and a diffuse transmission lobe. Made by Material.bsdf().

Batches: wi is (3,) (one incident direction for the batch) or (N, 3); wo is (3,) or (N, 3);
lambda_nm a number or (N,); the result has N entries. Directions are unit vectors in the BRDF
frame (x across the barbule, y along it, z the macro normal; wi toward the light, wo toward the
viewer); wavelengths must lie in the material's bins [lambda_nm[0], lambda_nm[-1] + bin_width_nm)
(floor binning, no interpolation). Each call runs on the calling thread with the GIL released.
Raises TypeError for non-numeric input, ValueError for wrong shapes, non-unit vectors or
wavelengths outside the material.)doc")
      .def_property_readonly("material", [](const Bsdf& b) { return b.material; }, "The Material it evaluates.")
      .def_property_readonly("transmission_albedo_requested", [](const Bsdf& b) { return b.bsdf->options().transmission_albedo; },
                             "The requested diffuse transmission albedo (granted per bin: transmission_albedo).")
      .def("eval",
           [](const Bsdf& b, const py::handle& wi, const py::handle& wo, const py::handle& lambda_nm,
              const std::optional<std::uint64_t>& instance) {
             return instance ? evaluate(b, wi, wo, lambda_nm, Value::instance, *instance)
                             : evaluate(b, wi, wo, lambda_nm, Value::mean, 0);
           },
           py::arg("wi"), py::arg("wo"), py::arg("lambda_nm"), py::arg("instance") = py::none(),
           "BSDF values f (sr⁻¹, not cosine-weighted), shape (N,): the mean BRDF f̄ (instance=None) "
           "or BRDF instance k (instance=k ≥ 0; noise functions 2k, 2k+1 of the material's pool), "
           "plus the diffuse transmission T_w/π for wo below wi's side.")
      .def("pdf",
           [](const Bsdf& b, const py::handle& wi, const py::handle& wo, const py::handle& lambda_nm) {
             return evaluate(b, wi, wo, lambda_nm, Value::pdf, 0);
           },
           py::arg("wi"), py::arg("wo"), py::arg("lambda_nm"),
           "Density per solid angle (sr⁻¹) of sample()'s wo over the whole sphere, shape (N,).")
      .def("sample", &sample, py::arg("wi"), py::arg("lambda_nm"), py::arg("u") = py::none(), py::kw_only(),
           py::arg("seed") = py::none(), py::arg("n") = py::none(), py::arg("instance") = py::none(),
           "Importance-samples the mean lobe (and the transmission lobe) with uniform numbers u, shape "
           "(N, 3) in [0, 1) (u[:, 0] picks the lobe, u[:, 1:] drive it), or with n rows drawn by "
           "numpy.random.default_rng(seed) (n None: one per wavelength). The library has no hidden "
           "random state: the same u give the same samples. Returns a dict: wo (N, 3), f (N,) of "
           "the mean or of instance k, pdf (N,) per solid angle, weight (N,) = f·|wo_z|/pdf (0 when "
           "pdf = 0), transmitted (N,) bool, and u when drawn from the seed.")
      .def("reflection_albedo",
           [](const Bsdf& b, const py::handle& wi_in, const py::handle& lambda_in, int strata) {
             if (strata < 1) throw py::value_error("strata must be >= 1");
             const Directions wi = directions(wi_in, "wi");
             const Wavelengths lambda = wavelengths(lambda_in, b.bsdf->material());
             const std::size_t n = batch_size({{wi.count, "wi"}, {lambda.count, "lambda_nm"}});
             py::array_t<double> out(static_cast<py::ssize_t>(n));
             double* a = out.mutable_data();
             py::gil_scoped_release release;
             Incidents incidents(*b.bsdf, wi, lambda);
             for (std::size_t k = 0; k < n; ++k) a[k] = b.bsdf->reflection_albedo(incidents.at(k), strata);
             return out;
           },
           py::arg("wi"), py::arg("lambda_nm"), py::arg("strata") = 64,
           "Reflected directional albedo A_r = ∫ f̄ cos θ_o dω over the upper hemisphere, shape (N,) "
           "(strata × strata stratified importance samples of the mean lobe).")
      .def("transmission_albedo",
           [](const Bsdf& b, const py::handle& lambda_in) {
             const Wavelengths lambda = wavelengths(lambda_in, b.bsdf->material());
             py::array_t<double> out(static_cast<py::ssize_t>(lambda.count ? lambda.count : 1));
             for (py::ssize_t k = 0; k < out.size(); ++k)
               out.mutable_data()[k] = b.bsdf->transmission_albedo(b.bsdf->material().wavelength_bin(lambda.at(k)));
             return out;
           },
           py::arg("lambda_nm"), "The diffuse transmission albedo T_w granted in each wavelength's bin, shape (N,).")
      .def("__repr__", [](const Bsdf& b) { return "<plumage.Bsdf of " + b.bsdf->material().label + ">"; });
}

}  // namespace plumage::python
