// Probe: mesh statistics of a species barbule (development tool, not a test).
#include <cstdio>
#include <map>

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
}
