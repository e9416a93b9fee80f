// `plumage bench ladder --quick` end to end (core/cli/bench_ladder.cpp, issue 9): every registered
// accuracy ladder runs, the CSV, chart and table are written, and each backend's rungs behave as
// its reference says they must — the ladder's numbers are checked, not only its files.
#include <catch2/catch.hpp>

#include "cli_run.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using plumage::cli_test::run_command;

namespace {

struct Rung {
  std::string backend, case_name, setting;
  double fidelity = 0, error = 0, wall_s = 0;
  bool pareto = false;
};

// The ladder CSV (fields may be double-quoted; no embedded newlines).
std::vector<Rung> read_ladder(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  REQUIRE(line == "backend,case,setting,fidelity,reference,metric,error,wall_s,cpu_s,pareto");
  std::vector<Rung> rungs;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::string cur;
    bool quoted = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
      const char c = line[i];
      if (quoted) {
        if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') cur += '"', ++i;
        else if (c == '"') quoted = false;
        else cur += c;
      } else if (c == '"') quoted = true;
      else if (c == ',') f.push_back(cur), cur.clear();
      else cur += c;
    }
    f.push_back(cur);
    REQUIRE(f.size() == 10);
    rungs.push_back({f[0], f[1], f[2], std::stod(f[3]), std::stod(f[6]), std::stod(f[7]), f[9] == "1"});
  }
  return rungs;
}

std::map<std::string, std::vector<Rung>> curves(const std::vector<Rung>& rungs, const std::string& backend) {
  std::map<std::string, std::vector<Rung>> out;
  for (const auto& r : rungs)
    if (r.backend == backend) out[r.case_name].push_back(r);
  return out;
}

}  // namespace

TEST_CASE("bench ladder --quick: every backend's ladder against its reference", "[cli][bench-ladder]") {
  const fs::path out = plumage::cli_test::fresh_scratch_path("plumage-test-bench-ladder", "quick");
  const auto r = run_command(std::string("cd ") + PLUMAGE_SOURCE_DIR + " && " + PLUMAGE_EXE +
                             " bench ladder --quick --out " + out.string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  REQUIRE(fs::exists(out / "ladder.csv"));
  CHECK(fs::file_size(out / "ladder.png") > 10000);
  CHECK(r.output.find("| backend | case | setting |") != std::string::npos);
  const auto rungs = read_ladder(out / "ladder.csv");

  for (const char* backend :
       {"multilayer", "bem", "pathtracer", "approximate", "bem (real barbule)", "fit", "fdtd_periodic"}) {
    INFO(backend);
    CHECK(!curves(rungs, backend).empty());
  }
  // Every curve has a Pareto-optimal rung, and its most accurate rung is one (of rungs tied at the
  // smallest error, the fastest is).
  for (const auto& r0 : rungs) {
    double best = 1e300;
    bool best_pareto = false;
    for (const auto& r1 : rungs) {
      if (r1.backend != r0.backend || r1.case_name != r0.case_name) continue;
      if (r1.error < best) best = r1.error, best_pareto = r1.pareto;
      else if (r1.error == best) best_pareto = best_pareto || r1.pareto;
    }
    INFO(r0.backend << " / " << r0.case_name);
    CHECK(best_pareto);
  }

  // Multilayer: the Airy recursion equals the closed-form periodic stack to rounding at any N.
  for (const auto& [name, c] : curves(rungs, "multilayer")) {
    for (const auto& r : c) {
      INFO(name << " " << r.setting);
      CHECK(r.error < 1e-12);
    }
  }
  // BEM on the cylinder: the acceptance level at 32 ppw and a convergence order above 2.5
  // (the far field converges at ≈ 3.3, plugins/bem/NOTES.md §4.4).
  for (const auto& [name, c] : curves(rungs, "bem")) {
    REQUIRE(c.size() >= 2);
    const Rung& coarse = c[c.size() - 2];
    const Rung& fine = c.back();
    INFO(name << ": " << coarse.setting << " " << coarse.error << ", " << fine.setting << " " << fine.error);
    CHECK(fine.error < 1e-3);
    CHECK(std::log(coarse.error / fine.error) / std::log(fine.fidelity / coarse.fidelity) > 2.5);
  }
  // FDTD: the layered stack converges to the closed form (the Yee error bound of
  // plugins/fdtd_periodic/NOTES.md §4: 8e-4 at 4 nm, ∝ h²), and on the crystal each finer rung is
  // closer to the finest, within issue 5's 2e-3 at the production step (10 nm).
  for (const auto& [name, c] : curves(rungs, "fdtd_periodic")) {
    REQUIRE(c.size() >= 2);
    INFO(name << ": " << c.front().setting << " " << c.front().error << ", " << c.back().setting << " " << c.back().error);
    CHECK(c.back().error < c.front().error);
    if (name.find("stack") != std::string::npos) {
      const double h_nm = 1.0 / c.back().fidelity;
      CHECK(c.back().error < 8e-4 * (h_nm / 4.0) * (h_nm / 4.0));
    } else {
      CHECK(c.back().error < 2e-3);
    }
  }
  // Path tracer: Monte Carlo error falls as spp^{-1/2} (slope between spp = 4 and 64).
  for (const auto& [name, c] : curves(rungs, "pathtracer")) {
    const Rung *a = nullptr, *b = nullptr;
    for (const auto& r : c) {
      if (r.fidelity == 4) a = &r;
      if (r.fidelity == 64) b = &r;
    }
    REQUIRE(a);
    REQUIRE(b);
    const double slope = std::log(b->error / a->error) / std::log(b->fidelity / a->fidelity);
    INFO(name << ": slope " << slope);
    CHECK(slope < -0.4);
    CHECK(slope > -0.6);
  }
  // Approximate against BEM on the real barbule: the BEM reference is converged far beyond the
  // approximate solver's model error (its own 8-ppw rung is at most half of that error), so
  // the approximate rungs measure the model, and the BEM's rungs improve with the mesh.
  double approx_min = 1e300;
  for (const auto& [name, c] : curves(rungs, "approximate"))
    for (const auto& r : c) approx_min = std::min(approx_min, r.error);
  const auto bem_real = curves(rungs, "bem (real barbule)");
  REQUIRE(bem_real.size() == 1);
  const auto& br = bem_real.begin()->second;
  REQUIRE(br.size() >= 2);
  INFO("approximate min error " << approx_min << ", bem " << br.front().error << " -> " << br.back().error);
  CHECK(br.back().error < br.front().error);
  CHECK(br.back().error < 0.5 * approx_min);
  // Fit: more instances bring the fitted lobe closer to the mean pattern of other instances.
  for (const auto& [name, c] : curves(rungs, "fit")) {
    INFO(name << ": " << c.front().error << " -> " << c.back().error);
    CHECK(c.back().error < c.front().error);
  }
}

TEST_CASE("bench ladder: an unknown ladder name is refused, naming the registered ones", "[cli][bench-ladder]") {
  const auto r = plumage::cli_test::run("bench ladder --quick --only nosuch --out /tmp/plumage-never-written");
  CHECK(r.status == 2);
  CHECK(r.output.find("no accuracy ladder named 'nosuch'") != std::string::npos);
  CHECK(r.output.find("multilayer") != std::string::npos);
  CHECK_FALSE(fs::exists("/tmp/plumage-never-written"));
}
