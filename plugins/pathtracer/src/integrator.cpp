#include "integrator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "plumage/conventions.hpp"

namespace plumage::pathtracer {

namespace {

constexpr double kInvPi = 1.0 / kPi;
constexpr int kRouletteFrom = 3;  // vertices before Russian roulette may end a path

double mean4(const Spectrum4& a) { return 0.25 * (a[0] + a[1] + a[2] + a[3]); }

double power_heuristic(double a, double b) {
  const double a2 = a * a, b2 = b * b;
  return a2 + b2 > 0.0 ? a2 / (a2 + b2) : 0.0;
}

V3 cosine_hemisphere(double u1, double u2) {
  const double r = std::sqrt(u1), phi = 2.0 * kPi * u2;
  return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1.0 - u1))};
}

V3 uniform_sphere(double u1, double u2) {
  const double z = 1.0 - 2.0 * u1, r = std::sqrt(std::max(0.0, 1.0 - z * z)), phi = 2.0 * kPi * u2;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// Unpolarised Fresnel reflectance of a smooth dielectric interface; eta = n_t / n_i.
double fresnel_dielectric(double cos_i, double eta, double* cos_t) {
  const double sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0) {
    *cos_t = 0.0;
    return 1.0;
  }
  const double ct = std::sqrt(1.0 - sin2_t);
  *cos_t = ct;
  const double rs = (cos_i - eta * ct) / (cos_i + eta * ct);
  const double rp = (eta * cos_i - ct) / (eta * cos_i + ct);
  return 0.5 * (rs * rs + rp * rp);
}

Direction dir(V3 v) { return {v.x, v.y, v.z}; }

}  // namespace

// A shading point: its material and what depends on (λ_j, ω_view) only.
struct Integrator::Vertex {
  SceneMaterial::Kind kind = SceneMaterial::Kind::diffuse;
  V3 p, ng, wv;  // position, unit geometric normal, unit direction toward the viewer
  Frame frame;   // feather: BRDF frame; diffuse: around the normal on the viewer's side
  const FeatherBsdf* bsdf = nullptr;
  std::array<FeatherBsdf::Incident, kWavelengths> in;  // at (λ_j, ω_view): the sampling proposal
  V3 wv_local;
  std::uint32_t material = 0;  // index into Scene::materials
  Spectrum4 lambda{};
  bool instance = false;
  std::uint64_t k = 0;
  Spectrum4 albedo{};
  double ior = 1.5;
};

Integrator::Integrator(const Scene& scene, const Settings& settings, const EmbreeScene& embree,
                       const SpectralTables& tables)
    : scene_(scene), settings_(settings), embree_(embree), tables_(tables) {
  // Float rays: a scene of extent X mm has float spacing ≈ 6e-8·X; 2e-6·X (≈ 30 ulps) keeps
  // secondary rays off their own triangle, far below a barbule's width (≥ 1e-3 mm) for X ≤ 500.
  eps_ = 2e-6 * std::max(1.0, embree.extent());
  env_pdf_ = scene.environment.radiance > 0.0 ? 1.0 / (4.0 * kPi) : 0.0;
  watched_of_material_.resize(scene.materials.size());
  for (std::size_t k = 0; k < scene.materials.size(); ++k) {
    const SceneMaterial& m = scene.materials[k];
    if (m.kind != SceneMaterial::Kind::feather || !m.feather) continue;
    const FeatherMaterial& fm = m.feather->material();
    for (MaterialWarning& w : parse_material_warnings(fm.warnings, fm.grid)) {
      if (!w.directional()) continue;
      watched_of_material_[k].push_back(watched_.size());
      watched_.push_back({static_cast<std::uint32_t>(k), std::move(w)});
    }
  }
}

void Integrator::observe(const Vertex& v, V3 wl, const Spectrum4& beta, const Spectrum4& fcos,
                         PathCounters& counters) const {
  const std::vector<std::size_t>& slots = watched_of_material_[v.material];
  if (slots.empty()) return;
  const V3 l = v.frame.to_local(wl);
  // The material's incident cosines (feather_bsdf.cpp, incident_geometry).
  const double ct = std::min(1.0, std::sqrt(l.x * l.x + l.z * l.z));
  const double cp = ct > 0.0 ? std::min(1.0, std::abs(l.z) / ct) : 0.0;
  double weight = 0.0;
  for (int j = 0; j < kWavelengths; ++j) weight += 0.25 * beta[j] * fcos[j];
  for (std::size_t slot : slots) {
    WarningTally& t = counters.warnings[slot];
    ++t.evaluations;
    t.weight_total += weight;
    if (watched_[slot].warning.contains(ct, cp)) {
      ++t.evaluations_in;
      t.weight_in += weight;
    }
  }
}

std::vector<WarningShare> Integrator::warning_shares(const std::vector<WarningTally>& totals) const {
  std::vector<WarningShare> out;
  for (std::size_t k = 0; k < watched_.size() && k < totals.size(); ++k) {
    const WatchedWarning& w = watched_[k];
    WarningShare share;
    share.material = scene_.materials[w.material].name;
    share.code = w.warning.code;
    share.directions = describe_cells(w.warning.grid, w.warning.cells);
    share.weight_in = totals[k].weight_in, share.weight_total = totals[k].weight_total;
    share.evaluations_in = totals[k].evaluations_in, share.evaluations = totals[k].evaluations;
    out.push_back(std::move(share));
  }
  return out;
}

V3 Integrator::offset_origin(V3 p, V3 ng, V3 toward) const {
  return p + (dot(ng, toward) >= 0.0 ? eps_ : -eps_) * ng;
}

void Integrator::shade_setup(Vertex& v, const Hit& hit, V3 d, double footprint_mm, const Spectrum4& lambda,
                             PathCounters& counters) const {
  const SceneMesh& mesh = scene_.meshes[hit.geom];
  const SceneMaterial& mat = scene_.materials[mesh.material];
  v.kind = mat.kind;
  v.material = mesh.material;
  v.wv = -d;
  switch (mat.kind) {
    case SceneMaterial::Kind::feather: {
      const V3 t = normalize(to_v3(mesh.frame_axis[hit.prim])), n = normalize(to_v3(mesh.frame_normal[hit.prim]));
      v.frame = {cross(t, n), t, n};
      v.bsdf = mat.feather.get();
      const V3 wl = v.frame.to_local(v.wv);
      v.wv_local = wl;
      v.lambda = lambda;
      // Level of detail (DESIGN §7): the cone's width projected on the surface, against the
      // spacing of the barbules it would average over.
      bool mean = true;
      if (settings_.lod == LevelOfDetail::instance) {
        mean = false;
      } else if (settings_.lod == LevelOfDetail::automatic) {
        const double cos_v = std::max(std::abs(wl.z), 0.05);
        mean = mesh.barbule_spacing_mm <= 0.0 ||
               footprint_mm / cos_v >= settings_.lod_barbules * mesh.barbule_spacing_mm;
      }
      v.instance = !mean;
      v.k = mesh.barbule_id.empty() ? 0 : mesh.barbule_id[hit.prim];
      ++counters.feather_points;
      if (mean) ++counters.feather_mean;
      counters.cache.get(*v.bsdf, lambda, dir(wl), v.in);
      break;
    }
    case SceneMaterial::Kind::diffuse: {
      const V3 n = dot(v.ng, v.wv) >= 0.0 ? v.ng : -v.ng;  // two-sided
      v.frame = Frame::around(n);
      for (int j = 0; j < kWavelengths; ++j) v.albedo[j] = mat.albedo.at(lambda[j]);
      break;
    }
    case SceneMaterial::Kind::dielectric:
      v.ior = mat.ior;
      break;
  }
}

// f_j·|cos θ_l| at every wavelength and the hero's pdf of sample() (solid angle, pdf[0]; the
// others are not needed by NEE and may be left unset), for the world direction wl to the light.
void Integrator::eval(const Vertex& v, V3 wl, Spectrum4& fcos, Spectrum4& pdf, IncidentCache& cache) const {
  switch (v.kind) {
    case SceneMaterial::Kind::feather: {
      // f(λ_j, ω_i = light, ω_o = viewer)·|cos θ_i| (feather_bsdf.hpp): one Incident per λ at the
      // light direction; the pdf is that of sample() below (the viewer-side lobe).
      const V3 l = v.frame.to_local(wl);
      const double c = std::abs(l.z);
      std::array<FeatherBsdf::Incident, kWavelengths> in;
      cache.get(*v.bsdf, v.lambda, dir(l), in);
      for (int j = 0; j < kWavelengths; ++j) {
        const double f = v.instance ? v.bsdf->eval(in[j], dir(v.wv_local), v.k) : v.bsdf->eval(in[j], dir(v.wv_local));
        fcos[j] = f * c;
      }
      // Only the hero's pdf enters the light/BSDF MIS weight (NEE does not change r).
      pdf[0] = v.bsdf->pdf(v.in[0], dir(l));
      return;
    }
    case SceneMaterial::Kind::diffuse: {
      const double c = dot(wl, v.frame.z);
      for (int j = 0; j < kWavelengths; ++j) {
        fcos[j] = c > 0.0 ? v.albedo[j] * kInvPi * c : 0.0;
        pdf[j] = c > 0.0 ? c * kInvPi : 0.0;
      }
      return;
    }
    case SceneMaterial::Kind::dielectric:
      fcos.fill(0.0);
      pdf.fill(0.0);
      return;
  }
}

bool Integrator::sample(const Vertex& v, PathSampler& rng, V3& wl, Spectrum4& fcos, Spectrum4& pdf, bool& specular,
                        bool& transmitted, IncidentCache& cache) const {
  specular = false;
  transmitted = false;
  const double uc = rng.next(), u1 = rng.next(), u2 = rng.next();
  switch (v.kind) {
    case SceneMaterial::Kind::feather: {
      // Proposal: the lobe of the viewer direction taken as ω_i (the BRDF is not reciprocal,
      // docs/validation.md "BSDF", but the lobe seen from the viewer is its closest cheap
      // approximation); the value is the true f with ω_i = the sampled light-side direction.
      const BsdfSample s = v.bsdf->sample(v.in[0], uc, u1, u2);
      if (!(s.pdf > 0.0)) return false;
      const V3 l{s.wo.x, s.wo.y, s.wo.z};
      wl = normalize(v.frame.to_world(l));
      transmitted = s.transmitted;
      const double c = std::abs(l.z);
      std::array<FeatherBsdf::Incident, kWavelengths> in;
      cache.get(*v.bsdf, v.lambda, s.wo, in);
      for (int j = 0; j < kWavelengths; ++j) {
        const double f = v.instance ? v.bsdf->eval(in[j], dir(v.wv_local), v.k) : v.bsdf->eval(in[j], dir(v.wv_local));
        fcos[j] = f * c;
        pdf[j] = j == 0 ? s.pdf : v.bsdf->pdf(v.in[j], s.wo);
      }
      return true;
    }
    case SceneMaterial::Kind::diffuse: {
      const V3 l = cosine_hemisphere(u1, u2);
      if (!(l.z > 0.0)) return false;
      wl = v.frame.to_world(l);
      for (int j = 0; j < kWavelengths; ++j) {
        fcos[j] = v.albedo[j] * kInvPi * l.z;
        pdf[j] = l.z * kInvPi;
      }
      return true;
    }
    case SceneMaterial::Kind::dielectric: {
      // Specular: fcos/pdf carry the ratio only (delta distributions cancel); the same for all λ
      // since the index is real and constant.
      specular = true;
      const bool entering = dot(v.wv, v.ng) > 0.0;
      const V3 n = entering ? v.ng : -v.ng;  // on the viewer's side
      const double eta = entering ? v.ior : 1.0 / v.ior;  // n_t / n_i
      const double cos_i = std::min(1.0, dot(v.wv, n));
      double cos_t = 0.0;
      const double F = fresnel_dielectric(cos_i, eta, &cos_t);
      double ratio = 1.0;
      if (uc < F) {
        wl = normalize(2.0 * cos_i * n - v.wv);
      } else {
        wl = normalize((-1.0 / eta) * v.wv + (cos_i / eta - cos_t) * n);
        transmitted = true;
        ratio = 1.0 / (eta * eta);  // radiance is compressed into the denser medium
      }
      fcos.fill(ratio);
      pdf.fill(1.0);
      return true;
    }
  }
  return false;
}

// One connection to each light (point, distant, area: a uniform point; environment: a uniform
// direction) from the surface vertex vx, weighted against BSDF sampling (power heuristic, hero
// pdf) and balanced over the wavelengths (1 / mean r); adds beta * f cos * radiance to L.
void Integrator::next_event(const Vertex& vx, const Spectrum4& beta, const Spectrum4& d65, double rmean,
                            PathSampler& rng, PathCounters& counters, Spectrum4& L) const {
  const V3 p = vx.p;
  Spectrum4 fcos, pdf;
  auto connect = [&](V3 wl, double dist, double light_pdf, double radiance_scale, bool delta) {
    eval(vx, wl, fcos, pdf, counters.cache);
    if (vx.kind == SceneMaterial::Kind::feather) observe(vx, wl, beta, fcos, counters);
    if (fcos[0] == 0.0 && fcos[1] == 0.0 && fcos[2] == 0.0 && fcos[3] == 0.0) return;
    ++counters.rays;
    if (embree_.occluded(offset_origin(p, vx.ng, wl), wl, dist)) return;
    // Balance over wavelengths (1/mean r), power heuristic light vs hero BSDF pdf.
    const double w = (delta ? 1.0 : power_heuristic(light_pdf, pdf[0])) / rmean;
    for (int j = 0; j < kWavelengths; ++j) L[j] += w * beta[j] * fcos[j] * radiance_scale * d65[j];
  };
  for (const PointLight& pl : scene_.point_lights) {
    const V3 to = to_v3(pl.position_mm) - p;
    const double dist2 = dot(to, to);
    if (dist2 <= 0.0) continue;
    const double dist = std::sqrt(dist2);
    connect((1.0 / dist) * to, dist * (1.0 - 1e-6), 1.0, pl.intensity / dist2, true);
  }
  for (const DistantLight& dl : scene_.distant_lights) {
    connect(normalize(to_v3(dl.toward_light)), std::numeric_limits<double>::infinity(), 1.0, dl.irradiance, true);
  }
  for (const AreaLight& a : scene_.area_lights) {
    const double s = rng.next(), t = rng.next();
    const V3 u = to_v3(a.edge_u_mm), v = to_v3(a.edge_v_mm);
    const V3 y = to_v3(a.corner_mm) + s * u + t * v;
    // Measured from the offset origin the shadow ray will start at (the offset shortens the
    // path by up to eps/cos, more than the stop-short margin below).
    const V3 to = y - offset_origin(p, vx.ng, y - p);
    const double dist2 = dot(to, to);
    const V3 un = cross(u, v);
    const double area = length(un);
    if (dist2 <= 0.0 || area <= 0.0) continue;
    const double dist = std::sqrt(dist2);
    const V3 wl = (1.0 / dist) * to;
    const double cos_l = -dot((1.0 / area) * un, wl);
    if (!a.two_sided && cos_l <= 0.0) continue;
    if (std::abs(cos_l) < 1e-12) continue;
    const double light_pdf = dist2 / (area * std::abs(cos_l));
    // The shadow ray stops short of the light's own surface.
    connect(wl, dist * (1.0 - 1e-5), light_pdf, a.radiance / light_pdf, false);
  }
  if (env_pdf_ > 0.0) {
    const double u1 = rng.next(), u2 = rng.next();
    const V3 wl = uniform_sphere(u1, u2);
    connect(wl, std::numeric_limits<double>::infinity(), env_pdf_, scene_.environment.radiance / env_pdf_, false);
  }
}

Spectrum4 Integrator::trace(V3 origin, V3 d, double spread, const Spectrum4& lambda, PathSampler& rng,
                            PathCounters& counters) const {
  Spectrum4 L{};
  Spectrum4 beta{1.0, 1.0, 1.0, 1.0};  // f/p of the hero's path pdf, per λ
  Spectrum4 r{1.0, 1.0, 1.0, 1.0};     // path pdf of λ_j relative to the hero's
  Spectrum4 d65{};
  for (int j = 0; j < kWavelengths; ++j) d65[j] = tables_.d65(lambda[j]);
  // MIS state of the last scattering: its hero BSDF pdf and mean(r) before it; specular or
  // camera: emitters count fully.
  bool last_specular = true;
  double last_pdf = 0.0, last_rmean = 1.0;
  double cone_width = 0.0;
  const std::size_t n_meshes = scene_.meshes.size();


  for (int depth = 1;; ++depth) {
    ++counters.rays;
    const Hit hit = embree_.intersect(origin, d);
    if (!hit.found) {
      const double env = scene_.environment.radiance;
      if (env > 0.0) {
        const double w = last_specular ? 1.0 : power_heuristic(last_pdf, env_pdf_);
        const double s = w / last_rmean;
        for (int j = 0; j < kWavelengths; ++j) L[j] += s * beta[j] * env * d65[j];
      }
      break;
    }
    cone_width += spread * hit.t;
    if (hit.geom >= n_meshes) {  // an area light
      const AreaLight& a = scene_.area_lights[hit.geom - n_meshes];
      const V3 u = to_v3(a.edge_u_mm), v = to_v3(a.edge_v_mm);
      const V3 un = cross(u, v);
      const double area = length(un);
      const V3 n = (1.0 / area) * un;
      const double cos_l = -dot(n, d);
      if (a.two_sided || cos_l > 0.0) {
        double w = 1.0;
        if (!last_specular) {
          const double light_pdf = hit.t * hit.t / (area * std::abs(cos_l));
          w = power_heuristic(last_pdf, light_pdf);
        }
        const double s = w / last_rmean;
        for (int j = 0; j < kWavelengths; ++j) L[j] += s * beta[j] * a.radiance * d65[j];
      }
      break;  // emitters do not scatter
    }

    // Vertex `depth` is a surface; past max_depth the path ends (the ray that reached it was
    // traced only for the emission it might have met, so the last vertex's BSDF sampling still
    // takes part in MIS).
    if (depth > settings_.max_depth) break;

    Vertex vx;
    {
      // The hit point from the barycentrics (on the triangle to float precision of the scene's
      // coordinates), not origin + t·dir, whose error grows with the distance travelled (a far
      // camera would otherwise put it below the surface and shadow rays would self-intersect).
      const SceneMesh& mesh = scene_.meshes[hit.geom];
      const auto& tri = mesh.triangles[hit.prim];
      const V3 p0 = to_v3(mesh.positions[tri[0]]), p1 = to_v3(mesh.positions[tri[1]]),
               p2 = to_v3(mesh.positions[tri[2]]);
      vx.ng = normalize(cross(p1 - p0, p2 - p0));
      vx.p = (1.0 - hit.u - hit.v) * p0 + hit.u * p1 + hit.v * p2;
    }
    const V3 p = vx.p;
    shade_setup(vx, hit, d, cone_width, lambda, counters);
    const double rmean = mean4(r);

    // Next-event estimation (not at specular vertices).
    if (vx.kind != SceneMaterial::Kind::dielectric) next_event(vx, beta, d65, rmean, rng, counters, L);

    // Continue by BSDF sampling at the hero wavelength.
    V3 wl;
    Spectrum4 fcos, pdf;
    bool specular = false, transmitted = false;
    if (!sample(vx, rng, wl, fcos, pdf, specular, transmitted, counters.cache)) break;
    if (vx.kind == SceneMaterial::Kind::feather) observe(vx, wl, beta, fcos, counters);
    if (specular) {
      for (int j = 0; j < kWavelengths; ++j) beta[j] *= fcos[j];
    } else {
      if (!(pdf[0] > 0.0)) break;
      for (int j = 0; j < kWavelengths; ++j) {
        beta[j] *= fcos[j] / pdf[0];
        r[j] *= pdf[j] / pdf[0];
      }
    }
    last_specular = specular;
    last_pdf = pdf[0];
    last_rmean = rmean;
    // Ray cone: rough scattering widens the cone (a crude but monotone spread model).
    if (!specular) spread += vx.kind == SceneMaterial::Kind::diffuse ? 1.0 : 0.2;

    const double m = mean4(r);
    if (!(m > 0.0)) break;
    if (depth >= kRouletteFrom) {
      const double q = std::min(1.0, std::max({beta[0], beta[1], beta[2], beta[3]}) / m);
      if (q <= 0.0) break;
      if (q < 1.0) {
        if (rng.next() >= q) break;
        for (double& b : beta) b /= q;
      }
    }
    origin = offset_origin(p, vx.ng, wl);
    d = wl;
  }
  return L;
}

}  // namespace plumage::pathtracer
