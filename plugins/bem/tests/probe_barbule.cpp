// Probe: mesh statistics of a species barbule (development tool, not a test).
#include <cstdio>
#include <chrono>
#include <map>
#include <string>

#include "bem_solver.hpp"
#include "plumage/species_config.hpp"
#include "plumage/structure_generator.hpp"
#include "test_registry.hpp"

int main(int argc, char** argv) {
  using namespace plumage;
  const auto cfg = load_species_config(argv[1], plumage::testing::registry());
  const double lambda = argc > 2 ? atof(argv[2]) : 550.0, ppw = argc > 3 ? atof(argv[3]) : 25.0;
  const CrossSection cs = cfg.structure->generate(0);
  std::printf("regions %zu, width %.0f nm\n", cs.regions.size(), cs.width_nm());
  const auto prep = bem::prepare_geometry(cs);
  double len = 0;
  for (const auto& e : prep->geometry.edges) len += norm(e.q - e.p);
  std::printf("interface edges %zu, total length %.1f um\n", prep->geometry.edges.size(), len / 1000);
  const auto mesh = bem::build_mesh(prep->geometry, lambda, ppw);
  int junctions = 0;
  std::map<int, int> valence;
  for (const auto& s : mesh.segments) valence[s.v0]++, valence[s.v1]++;
  for (auto [v, c] : valence) junctions += c > 2;
  std::printf("segments %zu, vertices %d, z-dofs %d, unknowns %d, junction vertices %d\n", mesh.segments.size(),
              mesh.n_t, mesh.n_z, mesh.unknowns(), junctions);
  double hmin = 1e9;
  for (const auto& s : mesh.segments) hmin = std::min(hmin, s.h);
  std::printf("min segment %.3f nm\n", hmin);
  // issue 9: what the near-touching detector sees (NOTES.md "Warnings (issue 9)")
  for (double ratio : {1e-5, 1e-3, 0.1, 0.5, 1.0, 2.0}) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto c = bem::closest_approach(mesh, ratio);
    std::printf("closest approach below gap/h %g: %d pairs, worst gap %.4g nm at h %.3g nm (%.2f s)\n", ratio, c.pairs,
                c.gap_nm, c.h_nm, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  std::printf("validate(): %zu problems\n", validate(cs).size());
  if (argc > 4) {  // solve: dense LU vs block-Jacobi GMRES, one plane wave per pol at θ = 0, φ = 0.3
    for (int method = 0; method < 2; ++method) {
      bem::BemOptions o;
      o.points_per_wavelength = ppw;
      o.max_dense_unknowns = 1 << 30;
      o.method = method ? bem::BemOptions::Method::gmres : bem::BemOptions::Method::dense;
      const auto sys = bem::build_system(prep->geometry, lambda, 0.0, o);
      Eigen::MatrixXcd B(sys->mesh.unknowns(), 2);
      for (int pol = 0; pol < 2; ++pol) bem::fill_rhs(sys->mesh, sys->k0, bem::plane_wave(0.0, 0.3, pol), B.col(pol));
      std::vector<int> its;
      const auto t0 = std::chrono::steady_clock::now();
      const Eigen::MatrixXcd X = sys->solve(B, o, &its);
      const double ts = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::printf("%s: assembly %.1f s, factor/precond %.1f s, solve 2 rhs %.1f s%s\n", method ? "gmres" : "dense",
                  sys->assembly_seconds, sys->factor_seconds, ts,
                  method ? (", iterations " + std::to_string(its[0]) + " / " + std::to_string(its[1])).c_str() : "");
    }
  }
}
