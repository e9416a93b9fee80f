#include "approximate_solver.hpp"

#include "plumage/param_table.hpp"

#include <Eigen/Dense>

#include <cmath>

#include "plumage/error.hpp"
#include "plumage/simd_math.hpp"
#include "eq2_currents.hpp"
#include "radiation.hpp"
#include "surface_validity.hpp"

namespace plumage {

namespace {

using Vec3 = std::array<double, 3>;
using CVec3 = std::array<Complex, 3>;

using detail::kGrazingCutoff;

// Everything about one instance that the far field needs, independent of λ and ω_i.
struct PreparedTop final : ScatteringSolver::Prepared {
  std::vector<Vec2> vertices;        // all top vertices, left to right
  std::vector<Vec2> normals;         // interior nodes 1..N−2
  std::vector<double> window;        // w(x_m)
  std::vector<double> node_length;   // d_m = half of each adjacent segment
  std::vector<double> regularity;    // amplitude factor (crystals), else 1
  std::vector<double> segment_length;  // |v_{k+1} − v_k|
  std::vector<LayerProfile> profiles;
  // Reflection sub-sampling (option `reflection_samples` K > 1): every segment split into K, the
  // local reflection and the currents evaluated at each interior sub-vertex (own normal, own
  // layer profile) and averaged over each node's tent support with the tent weights.
  int samples = 1;
  std::vector<Vec2> sample_normals;          // fine interior vertices 1 … (V−1)K − 1
  std::vector<LayerProfile> sample_profiles;
  std::shared_ptr<const LocalReflection> reflection;
  // Slope and curvature of the top under the window: the validity checks of surface_validity.hpp
  // (warnings approx.rough_surface, approx.high_curvature, approx.grazing).
  detail::TopSurfaceStatistics surface;
  std::string instance;        // detail::instance_name: who the per-geometry warnings name
  std::size_t instance_index = 0;
};

double dot3(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Jones matrices for every incident azimuth at every node ([a·nodes + m]) or, when the
// reflection is sub-sampled, at every sub-sample ([a·samples + f]). Points that face away from
// the light carry no current (point_currents) and their reflection is never read: they are not
// requested and stay zero (issue 26). The test is point_currents' with a margin of 1e-12, so
// that a different rounding of the same dot product (FMA contraction) cannot skip a point that
// point_currents lights.
// The result is a per-thread buffer, valid until the thread's next call (no fresh pages per
// solve(): 0.9 MB for a production group).
std::span<const JonesReflection> local_reflection(const PreparedTop& top, double lambda_nm, double theta_i_rad,
                                                  std::span<const double> phi_i_rad) {
  const bool sub = top.samples > 1;
  const std::vector<Vec2>& normals = sub ? top.sample_normals : top.normals;
  const std::vector<LayerProfile>& profiles = sub ? top.sample_profiles : top.profiles;
  const std::size_t points = normals.size();
  const double ct = std::cos(theta_i_rad), st = std::sin(theta_i_rad);
  const double lit = std::sin(kGrazingCutoff) - 1e-12;
  thread_local std::vector<LocalReflection::Request> requests;
  thread_local std::vector<std::size_t> where;  // index into the result of each request
  thread_local std::vector<JonesReflection> lit_jones;
  thread_local std::vector<JonesReflection> jones;
  requests.clear();
  where.clear();
  jones.resize(points * phi_i_rad.size());
  thread_local std::vector<double> psi;  // normal azimuths, once for all incident azimuths
  psi.resize(points);
  for (std::size_t m = 0; m < points; ++m) psi[m] = std::atan2(normals[m].x, normals[m].z);
  for (std::size_t a = 0; a < phi_i_rad.size(); ++a) {
    const Vec3 w_i{ct * std::sin(phi_i_rad[a]), st, ct * std::cos(phi_i_rad[a])};  // as in solve()
    for (std::size_t m = 0; m < points; ++m) {
      if (dot3(w_i, {normals[m].x, 0.0, normals[m].z}) <= lit) {
        jones[a * points + m] = {};  // never read; zero, as every entry is written once
        continue;
      }
      requests.push_back({lambda_nm, {theta_i_rad, phi_i_rad[a] - psi[m]},
                          profiles.empty() ? nullptr : &profiles[m]});
      where.push_back(a * points + m);
    }
  }
  lit_jones.resize(requests.size());
  top.reflection->reflect(requests, lit_jones);
  for (std::size_t i = 0; i < requests.size(); ++i) jones[where[i]] = lit_jones[i];
  return jones;
}

[[gnu::always_inline]] inline CVec3 cross3(const Vec3& a, const CVec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// 𝓔 = (k0/4)·sqrt(2/(iπγ0))·[ô × S_M − (I − ôô)·S_J]  (spec §4.1, paper Eq. 7), from the
// radiation integrals S_J = ∫ J̃ g and S_M = ∫ M g along the top.
CVec3 far_field_vector(Complex prefactor, const Vec3& o, const CVec3& sj, const CVec3& sm) {
  const Complex o_dot_j = o[0] * sj[0] + o[1] * sj[1] + o[2] * sj[2];
  const CVec3 o_cross_m = cross3(o, sm);
  CVec3 e;
  for (int c = 0; c < 3; ++c) e[c] = prefactor * (o_cross_m[c] - sj[c] + o[c] * o_dot_j);
  return e;
}

Complex far_field_prefactor(double k0, double gamma0) {
  return (k0 / 4.0) * std::sqrt(2.0 / (kPi * gamma0)) * std::polar(1.0, -kPi / 4);
}

// The per-node data the Eq. 2 currents read (eq2_currents.hpp).
detail::CurrentNodes current_nodes(const PreparedTop& top) {
  return {top.normals, top.window, top.node_length, top.regularity, top.segment_length, top.samples,
          top.sample_normals};
}

}  // namespace

std::shared_ptr<const ScatteringSolver::Prepared> ApproximateSolver::prepare(
    const CrossSection& section, std::shared_ptr<const LocalReflection> reflection) const {
  if (!reflection) {
    throw Error("approximate solver: no LocalReflection (the config's `reflection:` section)");
  }
  if (section.top.size() < 3) throw Error("approximate solver: the top surface has < 3 vertices");
  auto p = std::make_shared<PreparedTop>();
  p->reflection = std::move(reflection);
  p->vertices = section.top;
  const std::size_t n = section.top.size();
  const auto normals = vertex_normals(section.top);
  const double x0 = 0.5 * (section.top.front().x + section.top.back().x);
  const double s = window_fraction_ * section.width_nm();
  for (std::size_t i = 1; i + 1 < n; ++i) {
    p->normals.push_back(normals[i]);
    const double x = section.top[i].x - x0;
    p->window.push_back(std::exp(-(x * x) / (s * s)));
    p->node_length.push_back(0.5 * (norm(section.top[i] - section.top[i - 1]) +
                                    norm(section.top[i + 1] - section.top[i])));
    p->regularity.push_back(section.crystal && section.crystal->regularity.size() == n
                                ? section.crystal->regularity[i]
                                : 1.0);
  }
  for (std::size_t k = 0; k + 1 < n; ++k) {
    p->segment_length.push_back(norm(section.top[k + 1] - section.top[k]));
  }
  // Beyond the roughness checked against the full-wave BEM: say so (issue 9), never silently.
  p->surface = detail::top_surface_statistics(p->vertices, p->normals, p->window, p->node_length, s);
  p->instance = detail::instance_name(section);
  p->instance_index = static_cast<std::size_t>(section.instance);
  detail::warn_if_rough(p->surface, p->instance, p->instance_index);
  if (section.layered) {
    auto all = layer_profiles(section);
    p->profiles.assign(all.begin() + 1, all.end() - 1);
  }
  if (reflection_samples_ > 1) {
    // The same polyline with every segment split into K: its interior vertices are the samples.
    p->samples = reflection_samples_;
    CrossSection fine = section;
    fine.top.clear();
    for (std::size_t k = 0; k + 1 < n; ++k) {
      for (int q = 0; q < reflection_samples_; ++q) {
        const double t = static_cast<double>(q) / reflection_samples_;
        fine.top.push_back(section.top[k] + t * (section.top[k + 1] - section.top[k]));
      }
    }
    fine.top.push_back(section.top.back());
    const auto fine_normals = vertex_normals(fine.top);
    p->sample_normals.assign(fine_normals.begin() + 1, fine_normals.end() - 1);
    if (section.layered) {
      auto all = layer_profiles(fine);
      p->sample_profiles.assign(all.begin() + 1, all.end() - 1);
    }
  }
  return p;
}

// One solve()'s buffers (the Prepared instance, held by the caller, is not counted): the batch of
// local-reflection requests and answers, the current amplitudes and incident phases, the
// Radiator's (radiation.hpp: the larger of the chunked and the exact evaluation, since the
// directions' values are not known here) and the far fields. At θ_i = 0, where γ0 and so the
// chunks' sampling are largest.
MemoryEstimate ApproximateSolver::estimate_memory(const CrossSection& section, double lambda_nm, std::size_t n_phi_i,
                                                  std::size_t n_phi_o) const {
  MemoryEstimate e;
  const std::size_t verts = section.top.size();
  if (verts < 3) return e;
  const double nodes = static_cast<double>(verts - 2), n_phi = static_cast<double>(n_phi_i);
  const double points = reflection_samples_ > 1 ? static_cast<double>((verts - 1) * reflection_samples_ - 1) : nodes;
  const bool lossless = normalisation_ != Normalisation::eq9;
  const std::size_t columns = lossless ? 24 : 12;
  e.job = "approximate solve of " + std::to_string(verts - 2) + " top nodes x " + std::to_string(n_phi_i) +
          " incident azimuths at " + std::to_string(static_cast<int>(std::lround(lambda_nm))) + " nm";
  e.add("local reflection batch", points * n_phi * (sizeof(LocalReflection::Request) + sizeof(JonesReflection)));
  e.add("current amplitudes", nodes * n_phi * (static_cast<double>(columns) * 16.0) + static_cast<double>(verts) * n_phi * 8.0);
  std::vector<double> segment_length;
  for (std::size_t k = 0; k + 1 < verts; ++k) segment_length.push_back(norm(section.top[k + 1] - section.top[k]));
  std::vector<std::size_t> targets{n_phi_o};
  if (lossless) targets.push_back(static_cast<std::size_t>(kReferenceBins));
  const double gamma0 = wavenumber_per_nm(lambda_nm);
  double radiation = 0.0;
  for (bool on_cone : {true, false}) {
    radiation = std::max(radiation, detail::Radiator::estimate_bytes(section.top, segment_length, gamma0, targets, on_cone,
                                                                     chunking_, n_phi_i, columns));
  }
  e.add("far-field radiation", radiation);
  e.add("far fields", n_phi * static_cast<double>(n_phi_o) * 2.0 * 16.0);
  e.lower_with = {"outline.spacing_nm (fewer top nodes)", "a narrower segment (outline.width_um)",
                  "fewer incident azimuths (incident_grid)"};
  return e;
}

std::vector<FarField> ApproximateSolver::solve(const Prepared& prepared, double lambda_nm,
                                               double theta_i_rad,
                                               std::span<const double> phi_i_rad,
                                               std::span<const double> phi_o_rad) const {
  const auto& top = dynamic_cast<const PreparedTop&>(prepared);
  const std::size_t nodes = top.normals.size();
  const std::size_t n_phi = phi_i_rad.size();
  const std::size_t n_dir = phi_o_rad.size();
  const double k0 = wavenumber_per_nm(lambda_nm);
  const double ct = std::cos(theta_i_rad), st = std::sin(theta_i_rad);
  const double gamma0 = k0 * ct;  // transverse wavenumber in air

  // 0. Curvature and grazing beyond the range checked against the full-wave BEM: warnings.
  detail::warn_if_curved(top.surface, lambda_nm, top.instance, top.instance_index);
  for (std::size_t a = 0; a < phi_i_rad.size(); ++a)
    detail::warn_if_grazing(top.surface, lambda_nm, theta_i_rad, phi_i_rad[a], a);

  // 1. Local reflection under every node, for every incident azimuth, in one batch.
  const std::span<const JonesReflection> jones = local_reflection(top, lambda_nm, theta_i_rad, phi_i_rad);
  const std::size_t points = jones.size() / n_phi;  // nodes, or sub-samples

  // 2. Per azimuth: current amplitudes (Eq. 2, without the incident phase), then the far field
  // (radiation.hpp); with the `lossless` normalisation also the far field of the lossless
  // reference currents (fill_amplitudes) on the 400 pattern bins.
  std::vector<FarField> out(n_phi);
  const std::size_t verts = top.vertices.size();
  for (const Vec2& v : top.vertices) {
    if (2.0 * k0 * (std::abs(v.x) + std::abs(v.z)) > simd::kMaxReducibleArgument) {
      throw NumericalError("approximate solver: the cross section is too large for the far-field "
                           "phase range (|2·k0·ρ| > 1e5)");
    }
  }
  const Complex prefactor = far_field_prefactor(k0, gamma0);
  // Both `lossless` and `capped` radiate the lossless reference currents.
  const bool lossless = normalisation_ != Normalisation::eq9;
  static const std::vector<double> kPatternBins = pattern_directions(kReferenceBins).phi_o_rad;
  const auto n = static_cast<Eigen::Index>(nodes);
  const bool with_incident = currents_ == Currents::incident_and_reflected;
  // Everything of the far field that does not depend on φ_i is set up once for all azimuths
  // (radiation.hpp, Radiator); the currents of every azimuth are radiated together.
  std::vector<std::span<const double>> target_phis{phi_o_rad};
  if (lossless) target_phis.push_back(kPatternBins);
  detail::Radiator radiator(top.vertices, top.segment_length, gamma0, theta_i_rad, target_phis, chunking_);
  // Per-thread buffers, reused by the next solve() (no fresh pages per call).
  thread_local std::vector<Eigen::MatrixXcd> amplitudes;
  thread_local std::vector<std::vector<double>> chi;
  thread_local std::vector<Eigen::MatrixXcd> radiated;
  amplitudes.resize(n_phi);
  chi.resize(n_phi);
  for (std::size_t a = 0; a < n_phi; ++a) amplitudes[a].resize(n, lossless ? 24 : 12), chi[a].resize(verts);
  for (std::size_t a = 0; a < n_phi; ++a) {
    const IncidentDirection incident{theta_i_rad, phi_i_rad[a]};
    const double sp = std::sin(incident.phi_rad), cp = std::cos(incident.phi_rad);
    const Vec3 w_i{ct * sp, st, ct * cp};
    FarField& ff = out[a];
    ff.lambda_nm = lambda_nm;
    ff.incident = incident;
    ff.phi_o_rad.assign(phi_o_rad.begin(), phi_o_rad.end());
    // The currents and, with `lossless`, the lossless reference's in one pass (columns 12–23).
    detail::fill_amplitudes(current_nodes(top), incident, w_i, jones.subspan(a * points, points),
                    with_incident, amplitudes[a], ff.incident_power);
    // Incident phase k_i·ρ = −k0 ω_i·ρ at every vertex; the kernel integrates it exactly.
    for (std::size_t k = 0; k < verts; ++k) {
      chi[a][k] = -k0 * ct * (sp * top.vertices[k].x + cp * top.vertices[k].z);
    }
  }
  std::vector<detail::RadiationTargets> layout{{phi_o_rad, 0, 4, nullptr}};
  if (lossless) layout.push_back({kPatternBins, 4, 4, nullptr});
  radiator.radiate_all(std::span<const std::vector<double>>(chi.data(), n_phi),
                       std::span<const Eigen::MatrixXcd>(amplitudes.data(), n_phi), layout, radiated);
  // sin φ_o, cos φ_o once per solve, not per azimuth and polarization (issue 26).
  thread_local std::vector<double> sin_o, cos_o;
  sin_o.resize(n_dir), cos_o.resize(n_dir);
  for (std::size_t j = 0; j < n_dir; ++j) sin_o[j] = std::sin(phi_o_rad[j]), cos_o[j] = std::cos(phi_o_rad[j]);
  for (std::size_t a = 0; a < n_phi; ++a) {
    FarField& ff = out[a];
    const Eigen::MatrixXcd& main_out = radiated[a * layout.size()];
    for (int p = 0; p < 2; ++p) {
      ff.field[p].resize(n_dir);
      // The products written out in real arithmetic: std::complex's operator* calls __muldc3
      // (its NaN/∞ recovery; 0.8 % of the profile), and the radiated values are finite.
      const double pr = prefactor.real(), pi = prefactor.imag();
      const Complex* col1 = main_out.col(2 * p).data();
      const Complex* col2 = main_out.col(2 * p + 1).data();
      for (std::size_t j = 0; j < n_dir; ++j) {
        const double sj = sin_o[j], cj = cos_o[j];
        const Complex o1(pr * col1[j].real() - pi * col1[j].imag(), pr * col1[j].imag() + pi * col1[j].real());
        const Complex o2(pr * col2[j].real() - pi * col2[j].imag(), pr * col2[j].imag() + pi * col2[j].real());
        ff.field[p][j] = {o1 * cj + o2 * (st * sj), o2 * ct, -o1 * sj + o2 * (st * cj)};
      }
      if (lossless) {
        // Power the lossless reference currents send into the cone (Eq. 8 with their |𝓔|²,
        // midpoint rule on the pattern bins): the normaliser.
        const Eigen::MatrixXcd& reference_out = radiated[a * layout.size() + 1];
        double sum = 0.0;
        for (Eigen::Index j = 0; j < reference_out.rows(); ++j) {
          sum += std::norm(reference_out(j, 2 * p)) + std::norm(reference_out(j, 2 * p + 1));
        }
        const double reference = ct * std::norm(prefactor) * sum * (kPi / kReferenceBins) / (2.0 * kEta0_ohm);
        // `capped`: Eq. 9 unless the lossless reference radiates more than it, i.e. unless the
        // approximation would create energy; `lossless`: the reference itself.
        ff.incident_power[p] = normalisation_ == Normalisation::capped
                                   ? std::max(ff.incident_power[p], reference)
                                   : reference;
      }
    }
  }
  return out;
}

ApproximateSolver::NodeCurrents ApproximateSolver::currents(const Prepared& prepared,
                                                           double lambda_nm,
                                                           const IncidentDirection& incident) const {
  const auto& top = dynamic_cast<const PreparedTop&>(prepared);
  const std::size_t nodes = top.normals.size();
  const double k0 = wavenumber_per_nm(lambda_nm);
  const double ct = std::cos(incident.theta_rad);
  const double sp = std::sin(incident.phi_rad), cp = std::cos(incident.phi_rad);
  const double phi_i[1] = {incident.phi_rad};
  const std::span<const JonesReflection> jones = local_reflection(top, lambda_nm, incident.theta_rad, phi_i);
  Eigen::MatrixXcd amplitudes(static_cast<Eigen::Index>(nodes), 12);
  NodeCurrents out;
  detail::fill_amplitudes(current_nodes(top), incident, {ct * sp, std::sin(incident.theta_rad), ct * cp}, jones,
                  currents_ == Currents::incident_and_reflected, amplitudes, out.incident_power);
  for (std::size_t m = 0; m < nodes; ++m) {
    const Vec2 v = top.vertices[m + 1];
    out.position.push_back(v);
    const Complex phase = std::polar(1.0, -k0 * ct * (sp * v.x + cp * v.z));
    for (int p = 0; p < 2; ++p) {
      std::array<Complex, 6> c;
      for (int q = 0; q < 6; ++q) c[q] = amplitudes(static_cast<Eigen::Index>(m), 6 * p + q) * phase;
      out.current[p].push_back(c);
    }
  }
  return out;
}

FarField ApproximateSolver::solve_direct_sum(const Prepared& prepared, double lambda_nm,
                                            const IncidentDirection& incident,
                                            std::span<const double> phi_o_rad) const {
  const auto& top = dynamic_cast<const PreparedTop&>(prepared);
  const NodeCurrents cur = currents(prepared, lambda_nm, incident);
  const double k0 = wavenumber_per_nm(lambda_nm);
  const double ct = std::cos(incident.theta_rad), st = std::sin(incident.theta_rad);
  const double gamma0 = k0 * ct;
  const double gt[3] = {0.5 - 0.5 * std::sqrt(0.6), 0.5, 0.5 + 0.5 * std::sqrt(0.6)};
  const double gw[3] = {5.0 / 18, 8.0 / 18, 5.0 / 18};
  FarField ff;
  ff.lambda_nm = lambda_nm;
  ff.incident = incident;
  ff.phi_o_rad.assign(phi_o_rad.begin(), phi_o_rad.end());
  ff.incident_power = cur.incident_power;
  const Complex prefactor = far_field_prefactor(k0, gamma0);
  for (int p = 0; p < 2; ++p) ff.field[p].resize(phi_o_rad.size());
  for (std::size_t j = 0; j < phi_o_rad.size(); ++j) {
    const Vec3 o{ct * std::sin(phi_o_rad[j]), -st, ct * std::cos(phi_o_rad[j])};
    const double rx = std::sin(phi_o_rad[j]), rz = std::cos(phi_o_rad[j]);
    std::array<std::array<Complex, 6>, 2> sum{};
    for (std::size_t m = 0; m < cur.position.size(); ++m) {
      const Vec2 c = top.vertices[m + 1];
      for (const Vec2 end : {top.vertices[m], top.vertices[m + 2]}) {
        const double h = norm(end - c);
        for (int g = 0; g < 3; ++g) {
          // Tent value 1 − t at distance t·h from the node toward `end`.
          const Vec2 q = c + gt[g] * (end - c);
          const Complex w = gw[g] * h * (1.0 - gt[g]) * std::polar(1.0, -gamma0 * (rx * q.x + rz * q.z));
          for (int p = 0; p < 2; ++p) {
            for (int k = 0; k < 6; ++k) sum[p][k] += w * cur.current[p][m][k];
          }
        }
      }
    }
    for (int p = 0; p < 2; ++p) {
      ff.field[p][j] = far_field_vector(prefactor, o, {sum[p][0], sum[p][1], sum[p][2]},
                                        {sum[p][3], sum[p][4], sum[p][5]});
    }
  }
  return ff;
}

namespace {

// The solver's parameters, declared once (param_table.hpp).
struct ApproximateParams {
  ApproximateSolver::Currents currents = ApproximateSolver::Currents::reflected;
  double window_fraction = 0.25;
  ApproximateSolver::Normalisation normalisation = ApproximateSolver::Normalisation::capped;
  bool chunked = true;
  int reflection_samples = 1;
};

const ParamTable<ApproximateParams>& approximate_params() {
  using C = ApproximateSolver::Currents;
  using N = ApproximateSolver::Normalisation;
  static const auto table =
      ParamTable<ApproximateParams>{}
          .choice("currents", &ApproximateParams::currents,
                  {{"reflected", C::reflected}, {"incident_and_reflected", C::incident_and_reflected}}, C::reflected,
                  "reflected (E_r, H_r only, reference code) | incident_and_reflected (Eq. 2)")
          .number("window_fraction", &ApproximateParams::window_fraction, "1", 0.25, Limits::positive(),
                  "Gaussian window w(x) = exp(-x^2/s^2) with s = window_fraction * width")
          .choice("normalisation", &ApproximateParams::normalisation,
                  {{"capped", N::capped}, {"lossless", N::lossless}, {"eq9", N::eq9}}, N::capped,
                  "capped (Eq. 9, raised to the lossless reference where that radiates more) | lossless (power the "
                  "same currents radiate with |r| set to 1 at every node) | eq9 (paper Eq. 9)")
          .integer("reflection_samples", &ApproximateParams::reflection_samples, "1", 1, Limits::closed(1, 16),
                   "local reflection and currents at this many sub-samples per segment, tent-weighted per node "
                   "(1: nodes only)")
          .choice("far_field", &ApproximateParams::chunked, {{"chunked", true}, {"exact", false}}, true,
                  "chunked (band-limited interpolation, <= 1e-5 of exact) | exact (every node x direction)");
  return table;
}

}  // namespace

void register_approximate_solver(PluginRegistry& registry) {
  registry.builtin_registrar().add<ScatteringSolver>(
      {.type = "approximate",
       .version = "1.1.0",
       .summary = "paper §4: local reflection under each top node, Eq. 2 currents, 2.5D far "
                  "field on the specular cone (exact tent × plane-wave integrals, chunked "
                  "band-limited interpolation), Eq. 9 normalisation capped by its own lossless reference",
       .params = approximate_params().specs()},
      [](const ParamView& p, const PluginContext&) {
        const ApproximateParams o = approximate_params().read(p);
        detail::ChunkingOptions chunking;
        chunking.chunked = o.chunked;
        return std::make_unique<ApproximateSolver>(o.currents, o.window_fraction, o.normalisation, chunking,
                                                   o.reflection_samples);
      });
}

}  // namespace plumage
