// Probe (not a test): the measurements behind the BEM's stability warnings (NOTES.md "Warnings
// (issue 9)").
//   bem_probe_stability coarse        far-field error vs ppw: cylinders vs the exact series, and vs
//                                     a 4× finer mesh of the same polygon (mesh error alone)
//   bem_probe_stability gap [ppw]     near-touching bodies at fixed ppw as the gap shrinks, vs a
//                                     mesh refined toward the gap; energy balance (lossless)
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>

#include "bem_test_support.hpp"
#include "pair_integrals.hpp"

using namespace plumage;
using namespace plumage::bem;
using namespace plumage::bem::testing;

namespace {

double rel_l2_intensity(const Eigen::MatrixXcd& a, const Eigen::MatrixXcd& ref, int pol) {
  double num = 0, den = 0;
  for (Eigen::Index d = 0; d < a.rows() / 3; ++d) {
    double ia = 0, ir = 0;
    for (int c = 0; c < 3; ++c) ia += std::norm(a(3 * d + c, pol)), ir += std::norm(ref(3 * d + c, pol));
    num += (ia - ir) * (ia - ir);
    den += ir * ir;
  }
  return std::sqrt(num / den);
}

// |C_ext − C_sca| / C_ext of a lossless body (optical theorem vs far field over the full circle).
double energy_defect(const PlaneWaveResult& r, int pol, double theta, double phi_i, const std::vector<double>& phi_o) {
  const double k0 = r.sys->k0, g0 = k0 * std::cos(theta);
  const std::vector<double> fwd{phi_i + std::numbers::pi};
  const Eigen::MatrixXcd F = far_field_operator(r.sys->mesh, k0, theta, fwd) * r.x.col(pol);
  const auto e = incident_polarization(pol, {theta, phi_i}).e;
  const std::complex<double> proj = F(0) * e[0] + F(1) * e[1] + F(2) * e[2];
  const std::complex<double> t = proj / (std::sqrt(2.0 / (std::numbers::pi * g0)) * std::polar(1.0, 0.75 * std::numbers::pi));
  const double ext = 4.0 / k0 * t.real();
  double sum = 0.0;
  for (std::size_t d = 0; d < phi_o.size(); ++d) {
    for (int c = 0; c < 3; ++c) sum += std::norm(r.field(3 * d + c, pol));
  }
  const double sca = std::cos(theta) * sum * 2.0 * std::numbers::pi / phi_o.size();
  return std::abs(ext - sca) / std::abs(ext);
}

double point_seg(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 d = b - a;
  const double t = std::clamp(dot(p - a, d) / dot(d, d), 0.0, 1.0);
  return norm(p - (a + t * d));
}

// Splits every outline edge (collinearly: the geometry is unchanged) until each piece is no longer
// than `ratio` × its distance to the other regions' outlines (floor `min_len`).
CrossSection refine_toward_gaps(const CrossSection& cs, double ratio, double min_len) {
  CrossSection out = cs;
  for (std::size_t r = 0; r < cs.regions.size(); ++r) {
    const Polygon& poly = cs.regions[r].outline;
    auto dist_to_others = [&](Vec2 a, Vec2 b) {
      double d = 1e300;
      for (std::size_t o = 0; o < cs.regions.size(); ++o) {
        if (o == r) continue;
        const Polygon& q = cs.regions[o].outline;
        for (std::size_t k = 0; k < q.size(); ++k) {
          const Vec2 c = q[k], e = q[(k + 1) % q.size()];
          d = std::min({d, point_seg(a, c, e), point_seg(b, c, e), point_seg(c, a, b), point_seg(e, a, b)});
        }
      }
      return d;
    };
    Polygon np;
    std::function<void(Vec2, Vec2)> split = [&](Vec2 a, Vec2 b) {
      const double len = norm(b - a);
      if (len <= min_len || len <= ratio * dist_to_others(a, b)) {
        np.push_back(a);
        return;
      }
      const Vec2 m = 0.5 * (a + b);
      split(a, m);
      split(m, b);
    };
    for (std::size_t k = 0; k < poly.size(); ++k) split(poly[k], poly[(k + 1) % poly.size()]);
    out.regions[r].outline = np;
  }
  return out;
}

Polygon rect(double x0, double z0, double x1, double z1) { return {{x0, z0}, {x1, z0}, {x1, z1}, {x0, z1}}; }

void coarse() {
  const auto phi_o = full_circle(360);
  const double phi_i = 0.4;
  struct Case {
    const char* name;
    std::vector<double> radii;
    std::vector<Material> mats;
    double lambda, theta_deg;
  };
  const std::vector<Case> cases = {
      {"keratin r=250 550 th30", {250.0}, {Material::keratin()}, 550, 30},
      {"coated 250+100 550 th30", {250.0, 350.0}, {Material::keratin(), Material::melanin()}, 550, 30},
      {"melanin r=100 400 th0", {100.0}, {Material::melanin()}, 400, 0},
      {"keratin r=1000 700 th0", {1000.0}, {Material::keratin()}, 700, 0},
      {"keratin r=1000 400 th30", {1000.0}, {Material::keratin()}, 400, 30},
  };
  for (const auto& c : cases) {
    if (std::getenv("BLOCK_ONLY")) break;
    const double lambda = c.lambda, theta = c.theta_deg * std::numbers::pi / 180;
    std::vector<std::complex<double>> m;
    std::vector<double> rum;
    for (std::size_t k = 0; k < c.radii.size(); ++k) m.push_back(c.mats[k].index(lambda)), rum.push_back(c.radii[k] / 1000);
    for (double ppw : {5.0, 6.0, 8.0, 10.0, 12.0, 16.0, 24.0}) {
      BemOptions opt;
      opt.points_per_wavelength = ppw;
      const auto cs = layered_cylinder(c.radii, c.mats, lambda, ppw, 12);
      const auto res = solve_plane_wave(cs, lambda, theta, phi_i, phi_o, opt);
      BemOptions fine = opt;
      fine.points_per_wavelength = 4 * ppw;
      const auto ref = solve_plane_wave(cs, lambda, theta, phi_i, phi_o, fine);
      double es = 0, em = 0;
      for (int pol = 0; pol < 2; ++pol) {
        es = std::max(es, compare_with_series(res.field, pol, oracle::solve_layered(rum, m, lambda / 1000, theta, pol + 1),
                                              phi_i, phi_o).intensity_l2);
        em = std::max(em, rel_l2_intensity(res.field, ref.field, pol));
      }
      std::printf("%-26s ppw %4.0f N %5d: vs series %.2e   vs 4x mesh, same polygon %.2e\n", c.name, ppw,
                  res.sys->mesh.unknowns(), es, em);
      std::fflush(stdout);
    }
  }
  // Straight edges only (the polygon does not change with ppw): keratin block 1000 x 300 nm.
  for (double lambda : {400.0, 550.0}) {
    CrossSection cs;
    cs.label = "block";
    cs.regions.push_back({rect(-500, -150, 500, 150), Material::keratin(), RegionRole::body});
    const double theta = 0.5;
    BemOptions fine;
    fine.points_per_wavelength = 96;
    const auto ref = solve_plane_wave(cs, lambda, theta, phi_i, phi_o, fine);
    std::vector<double> ppws{5.0, 6.0, 8.0, 10.0, 12.0, 16.0, 24.0};
    if (std::getenv("BLOCK_ONLY")) ppws = {13, 14, 15, 16, 17, 18, 19, 20, 21, 22, 23, 24, 26, 28, 30};
    for (double ppw : ppws) {
      BemOptions opt;
      opt.points_per_wavelength = ppw;
      const auto res = solve_plane_wave(cs, lambda, theta, phi_i, phi_o, opt);
      double em = 0;
      for (int pol = 0; pol < 2; ++pol) em = std::max(em, rel_l2_intensity(res.field, ref.field, pol));
      std::printf("keratin block 1000x300 %3.0f ppw %4.0f N %5d: vs 96 ppw %.2e\n", lambda, ppw, res.sys->mesh.unknowns(), em);
      std::fflush(stdout);
    }
  }
}

void gap(double ppw, int geometry0) {
  const auto phi_o = full_circle(360);
  const double phi_i = 0.4, lambda = std::getenv("LAMBDA") ? std::atof(std::getenv("LAMBDA")) : 550.0,
               theta = 20.0 * std::numbers::pi / 180;
  for (int geometry = geometry0; geometry < (std::getenv("ONLY") ? geometry0 + 1 : 3); ++geometry) {
    std::vector<double> gaps{40.0, 20.0, 10.0, 5.0, 2.0, 1.0, 0.5, 0.2, 0.1};
    if (const char* env = std::getenv("GAPS")) {  // e.g. GAPS="0.01,0.001,-1"
      gaps.clear();
      for (char* p = const_cast<char*>(env); *p;) {
        gaps.push_back(std::strtod(p, &p));
        if (*p == ',') ++p;
      }
    }
    for (double g : gaps) {
      if (geometry == 0 && g < 1.0 && !std::getenv("GAPS")) continue;
      CrossSection cs;
      const char* name = "";
      if (geometry == 0) {
        name = "two blocks (slot)";
        cs.regions.push_back({rect(-300 - g / 2, -150, -g / 2, 150), Material::constant(1.56), RegionRole::body});
        cs.regions.push_back({rect(g / 2, -150, 300 + g / 2, 150), Material::constant(1.56), RegionRole::body});
      } else if (geometry == 1) {
        name = "two cylinders r=150";
        Polygon a = circle_polygon(150, 96), b = a;
        const double rr = a[0].x;  // vertex at angle 0: the polygon's extreme point
        for (auto& p : a) p.x -= rr + g / 2;
        for (auto& p : b) p.x += rr + g / 2;
        cs.regions.push_back({a, Material::constant(1.56), RegionRole::body});
        cs.regions.push_back({b, Material::constant(1.56), RegionRole::body});
      } else {
        name = "rod under the surface";
        cs.regions.push_back({rect(-300, -150, 300, 150), Material::constant(1.56), RegionRole::body});
        Polygon c = circle_polygon(60, 64);
        // vertex 16 of 64 is the top (angle π/2)
        const double top = c[16].z;
        for (auto& p : c) p.z += 150 - g - top;
        Region rod{c, Material::constant(2.0), RegionRole::rod};
        rod.parent = 0;
        cs.regions.push_back(rod);
      }
      BemOptions opt;
      opt.points_per_wavelength = ppw;
      if (const char* e = std::getenv("NEARF")) opt.quadrature.near_factor = std::atof(e);
      if (const char* e = std::getenv("FARP")) opt.quadrature.far_points = std::atoi(e);
      if (const char* e = std::getenv("INNER")) opt.quadrature.inner_regular = std::atoi(e);
      if (const char* e = std::getenv("PIECES")) opt.quadrature.near_pieces = std::atoi(e);
      if (const char* e = std::getenv("CORNER")) opt.corner_split_deg = std::atof(e);
      auto t0 = std::chrono::steady_clock::now();
      const auto res = solve_plane_wave(cs, lambda, theta, phi_i, phi_o, opt);
      const double t_res = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (std::getenv("COND")) {
        const Eigen::MatrixXcd Z = assemble_dense(res.sys->mesh, res.sys->media, res.sys->k0, res.sys->beta, opt.quadrature);
        Eigen::BDCSVD<Eigen::MatrixXcd> svd(Z);
        const auto& sv = svd.singularValues();
        std::printf("   singular values: max %.3e min %.3e (cond %.2e), next smallest %.3e %.3e\n", sv(0), sv(sv.size() - 1),
                    sv(0) / sv(sv.size() - 1), sv(sv.size() - 2), sv(sv.size() - 3));
      }
      // h of the mesh next to the gap: the shortest of the longest segments of the two nearest edges
      double hmin_near = 1e300, gap_seg = 1e300;
      const Mesh& m = res.sys->mesh;
      for (const auto& A : m.segments) {
        for (const auto& B : m.segments) {
          if (&A == &B || A.v0 == B.v0 || A.v0 == B.v1 || A.v1 == B.v0 || A.v1 == B.v1) continue;
          if ((A.a == B.a && A.b == B.b)) continue;
          const double d = segment_distance(A, B);
          if (d < gap_seg) gap_seg = d, hmin_near = std::max(A.h, B.h);
        }
      }
      // references: the same body at 2x and 4x the ppw everywhere, and refined toward the gap
      // (pieces no longer than half their distance to the other region) at the production ppw
      double e2 = -1, e4 = -1, eg = -1, eb2 = -1, eb4 = -1, ebg = -1;
      int n4 = 0, ng = 0;
      auto cmp = [&](const PlaneWaveResult& a, const PlaneWaveResult& b) {
        double e = 0;
        for (int pol = 0; pol < 2; ++pol) e = std::max(e, rel_l2_intensity(a.field, b.field, pol));
        return e;
      };
      auto defect = [&](const PlaneWaveResult& a) {
        double e = 0;
        for (int pol = 0; pol < 2; ++pol) e = std::max(e, energy_defect(a, pol, theta, phi_i, phi_o));
        return e;
      };
      const CrossSection graded = refine_toward_gaps(cs, 0.5, 0.01);
      BemOptions o2 = opt, o4 = opt;
      o2.points_per_wavelength = 2 * ppw;
      o4.points_per_wavelength = 4 * ppw;
      const auto r4 = solve_plane_wave(cs, lambda, theta, phi_i, phi_o, o4);
      const auto r2 = solve_plane_wave(cs, lambda, theta, phi_i, phi_o, o2);
      n4 = r4.sys->mesh.unknowns();
      e4 = cmp(res, r4), e2 = cmp(r2, r4), eb4 = defect(r4), eb2 = defect(r2);
      if (g > 0 && build_mesh(prepare_geometry(graded)->geometry, lambda, ppw).unknowns() <= 8000) {
        const auto rg = solve_plane_wave(graded, lambda, theta, phi_i, phi_o, opt);
        ng = rg.sys->mesh.unknowns();
        eg = cmp(res, rg), ebg = defect(rg);
        std::printf("   graded vs 4x: %.2e\n", cmp(rg, r4));
      }
      std::printf("%-22s ppw %3.0f gap %5.2f nm h %5.2f gap/h %.3f N %5d: vs 4x ppw (N %5d) %.2e [2x vs 4x %.1e] vs graded (N %5d) "
                  "%.2e | energy defect %.1e, 2x %.1e, 4x %.1e, graded %.1e  %.1fs\n",
                  name, ppw, gap_seg, hmin_near, gap_seg / hmin_near, m.unknowns(), n4, e4, e2, ng, eg, defect(res), eb2, eb4, ebg, t_res);
      std::fflush(stdout);
    }
  }
}

// Condition estimate of the dense LU (1/rcond, 1-norm) against the far-field error, healthy and
// unhealthy meshes (NOTES.md §6.2).
void cond() {
  const auto phi_o = full_circle(360);
  const double phi_i = 0.4, theta = std::getenv("THETA") ? std::atof(std::getenv("THETA")) : 20.0 * std::numbers::pi / 180;
  auto run = [&](const char* name, const CrossSection& cs, double lambda, double ppw) {
    BemOptions opt, o4;
    opt.points_per_wavelength = ppw;
    if (const char* e = std::getenv("CORNER")) opt.corner_split_deg = std::atof(e);  // 180: shared tents (before)
    o4 = opt;
    o4.points_per_wavelength = 4 * ppw;
    const auto res = solve_plane_wave(cs, lambda, theta, phi_i, phi_o, opt);
    const double rc = res.sys->lu->rcond();
    const auto ref = solve_plane_wave(cs, lambda, theta, phi_i, phi_o, o4);
    double e = 0;
    for (int pol = 0; pol < 2; ++pol) e = std::max(e, rel_l2_intensity(res.field, ref.field, pol));
    double hmin = 1e300, hmax = 0;
    for (const auto& sgm : res.sys->mesh.segments) hmin = std::min(hmin, sgm.h), hmax = std::max(hmax, sgm.h);
    std::printf("%-34s %4.0f nm ppw %3.0f N %5d: cond1 ~ %.2e (cond x hmin/lambda %.2e)  vs 4x %.2e\n", name, lambda, ppw,
                res.sys->mesh.unknowns(), 1.0 / rc, hmin / lambda / rc, e);
    std::fflush(stdout);
  };
  const char* only = std::getenv("ONLY");
  if (!only || *only == 'c') {
    for (double ppw : {15.0, 30.0}) {
      run("keratin cylinder r=250", layered_cylinder({250.0}, {Material::keratin()}, 550, ppw), 550, ppw);
      run("coated 250+100", layered_cylinder({250.0, 350.0}, {Material::keratin(), Material::melanin()}, 550, ppw), 550, ppw);
      run("keratin cylinder r=1000", layered_cylinder({1000.0}, {Material::keratin()}, 700, ppw), 700, ppw);
      run("junction body", junction_body(), 550, ppw);
    }
  }
  if (only && *only == 'p') {  // the 1000 x 300 nm keratin block of coarse(), ppw sweep at 550 nm
    CrossSection cs;
    cs.regions.push_back({rect(-500, -150, 500, 150), Material::keratin(), RegionRole::body});
    for (double ppw : {13.0, 14.0, 15.0, 16.0, 17.0, 20.0, 21.0, 22.0, 23.0, 30.0}) run("keratin block 1000x300", cs, 550, ppw);
  }
  if (!only || *only == 'b') {
    for (double lambda = 500; lambda <= 600; lambda += 10) {
      CrossSection cs;
      cs.regions.push_back({rect(-150, -150, 150, 150), Material::constant(1.56), RegionRole::body});
      run("block 300x300 n=1.56", cs, lambda, 30);
    }
  }
  if (!only || *only == 's') {
    for (double g : {1000.0, 40.0, 20.0, 15.0, 2.0}) {
      CrossSection cs;
      cs.regions.push_back({rect(-300 - g / 2, -150, -g / 2, 150), Material::constant(1.56), RegionRole::body});
      cs.regions.push_back({rect(g / 2, -150, 300 + g / 2, 150), Material::constant(1.56), RegionRole::body});
      char name[64];
      std::snprintf(name, sizeof name, "slot %g nm", g);
      run(name, cs, 550, 30);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  const char* what = argc > 1 ? argv[1] : "coarse";
  if (!std::strcmp(what, "coarse")) coarse();
  else if (!std::strcmp(what, "cond")) cond();
  else gap(argc > 2 ? std::atof(argv[2]) : 30.0, argc > 3 ? std::atoi(argv[3]) : 0);
}
