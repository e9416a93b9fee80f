// `plumage compare` and `plumage simulate --directions full` as a user runs them: outputs exist
// and agree with each other, a method compared with itself gives correlation 1 and L2 0 exactly
// while a different method does not, config errors name file:line and the field with nothing
// written, and (with the bem plug-in) the full-circle scattering width of a cylinder matches the
// exact series, which checks the normalisation stated in the CSV header.
#include <catch2/catch.hpp>

#include "cli_run.hpp"

#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#ifdef PLUMAGE_HAVE_BEM
#include "cylinder_series.hpp"
#endif

namespace fs = std::filesystem;
using plumage::cli_test::Result;
using plumage::cli_test::run;
using plumage::cli_test::run_command;

namespace {

fs::path scratch(const std::string& name) { return plumage::cli_test::fresh_scratch_path("plumage-test-compare", name); }

std::string source(const std::string& rel) { return std::string(PLUMAGE_SOURCE_DIR) + "/" + rel; }

// A CSV without its '#' comment lines, as rows of named text fields.
std::vector<std::map<std::string, std::string>> read_csv(const fs::path& file) {
  std::ifstream in(file);
  REQUIRE(in.good());
  std::string line;
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
  auto split = [](const std::string& l) {
    std::vector<std::string> out;
    std::stringstream s(l);
    std::string f;
    while (std::getline(s, f, ',')) out.push_back(f);
    return out;
  };
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header.empty()) { header = split(line); continue; }
    const auto f = split(line);
    REQUIRE(f.size() == header.size());
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < f.size(); ++i) row[header[i]] = f[i];
    rows.push_back(std::move(row));
  }
  return rows;
}

double num(const std::map<std::string, std::string>& row, const std::string& key) {
  return std::stod(row.at(key));
}

bool is_png(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  char magic[8] = {};
  in.read(magic, 8);
  return in.good() && std::string(magic + 1, 3) == "PNG";
}

}  // namespace

TEST_CASE("plumage compare: a tiny approximate-against-approximate comparison", "[cli][compare]") {
  const fs::path out = scratch("tiny");
  const auto r = run("compare " + source("tests/cli/data/compare-tiny.yaml") + " --out " + out.string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  for (const char* f : {"tiny-metrics.csv", "tiny-patterns.csv", "tiny-times.csv"}) CHECK(fs::exists(out / f));
  for (const char* f : {"tiny-patterns-theta0_phi0.png", "tiny-patterns-theta0_phim30.png",
                        "tiny-colours-theta0_phi0.png", "tiny-colours-theta0_phim30.png", "tiny-error-vs-cost.png"}) {
    INFO(f);
    CHECK(is_png(out / f));
  }
  // No temporary files left behind.
  for (const auto& e : fs::directory_iterator(out)) CHECK(e.path().string().find(".tmp") == std::string::npos);

  const auto metrics = read_csv(out / "tiny-metrics.csv");
  // 4 methods x 2 incident directions x 3 wavelengths x 3 polarizations (1, 2, mean).
  REQUIRE(metrics.size() == 4u * 2 * 3 * 3);
  int differing = 0;
  for (const auto& row : metrics) {
    INFO(row.at("method") << " " << row.at("lambda_nm") << " nm, phi_i " << row.at("phi_i_deg") << ", pol " << row.at("pol"));
    CHECK(row.at("reference") == "reflected");
    const double corr = num(row, "correlation"), l2 = num(row, "rel_l2");
    const double R = num(row, "R_method"), Rref = num(row, "R_reference");
    CHECK(std::isfinite(corr));
    CHECK(corr <= 1.0);
    CHECK(corr >= -1.0);
    CHECK(l2 >= 0.0);
    CHECK(R > 0.0);
    CHECK(R < 2.0);
    CHECK(num(row, "dR") == Approx(R - Rref).margin(1e-8));
    const std::string& m = row.at("method");
    if (m == "reflected" || m == "reflected_again" || m == "reflected_reduced") {
      // Deterministic runs of the same solver (the approximate solver ignores the regions, so
      // the reduced layer geometry changes nothing for it): bit-identical patterns.
      CHECK(row.at("correlation") == "1");
      CHECK(row.at("rel_l2") == "0");
      CHECK(row.at("dR") == "0");
    } else {
      REQUIRE(m == "incident_and_reflected");
      if (corr < 1.0 && l2 > 1e-4 && std::abs(R - Rref) > 1e-6) ++differing;
    }
  }
  // The other current option changes every pattern.
  CHECK(differing == 2 * 3 * 3);

  // The reflected fractions are the integrals of the written patterns (midpoint rule, 90 bins).
  const auto patterns = read_csv(out / "tiny-patterns.csv");
  CHECK(patterns.size() == 4u * 2 * 3 * 3 * 90);
  std::map<std::string, double> integral;
  for (const auto& p : patterns) {
    integral[p.at("method") + "/" + p.at("phi_i_deg") + "/" + p.at("lambda_nm") + "/" + p.at("pol")] +=
        num(p, "density_per_rad") * M_PI / 90.0;
  }
  for (const auto& row : metrics) {
    const std::string key = row.at("method") + "/" + row.at("phi_i_deg") + "/" + row.at("lambda_nm") + "/" + row.at("pol");
    INFO(key);
    CHECK(integral.at(key) == Approx(num(row, "R_method")).epsilon(1e-6));
  }

  const auto times = read_csv(out / "tiny-times.csv");
  REQUIRE(times.size() == 4);
  for (const auto& t : times) {
    CHECK(num(t, "total_s") > 0.0);
    CHECK(num(t, "total_s") == Approx(num(t, "prepare_s") + num(t, "solve_s")).epsilon(1e-4));
    CHECK(t.at("solver") == "approximate");
  }
  CHECK(times[2].at("geometry") == "reduced_layers");
  // The solver section as written, one CSV cell (commas and double quotes replaced).
  CHECK(times[0].at("options") == "{'type': 'approximate'; 'currents': 'reflected'}");
  CHECK(times[3].at("options") == "{'type': 'approximate'; 'currents': 'incident_and_reflected'}");
  // The summary table on stdout names the reference.
  CHECK_THAT(r.output, Catch::Contains("(reference)") && Catch::Contains("incident_and_reflected"));
}

TEST_CASE("plumage compare --instance: another barbule of the same comparison", "[cli][compare]") {
  // The config's instance (0) against --instance 0 and --instance 2: the same patterns, then different
  // ones; the files name the instance that was run.
  const auto patterns_of = [](const fs::path& out, const std::string& extra) {
    const auto r = run("compare " + source("tests/cli/data/compare-tiny.yaml") + " --out " + out.string() +
                       " --no-pictures --only reflected --wavelengths 550" + extra);
    INFO(r.output);
    REQUIRE(r.status == 0);
    std::vector<double> u;
    for (const auto& p : read_csv(out / "tiny-patterns.csv")) u.push_back(num(p, "density_per_rad"));
    return std::make_pair(u, r.output);
  };
  const auto [config_default, out_default] = patterns_of(scratch("instance-default"), "");
  const auto [explicit0, out0] = patterns_of(scratch("instance-0"), " --instance 0");
  const fs::path dir2 = scratch("instance-2");
  const auto [other, out2] = patterns_of(dir2, " --instance 2");
  CHECK_THAT(out_default, Catch::Contains("instance 0,"));
  CHECK_THAT(out2, Catch::Contains("instance 2,"));
  std::ifstream header(dir2 / "tiny-metrics.csv");
  std::string first;
  std::getline(header, first);
  CHECK_THAT(first, Catch::Contains("instance 2,"));
  REQUIRE(config_default.size() == other.size());
  CHECK(config_default == explicit0);
  double diff = 0, norm = 0;
  for (std::size_t i = 0; i < other.size(); ++i) diff += std::abs(other[i] - config_default[i]), norm += std::abs(config_default[i]);
  CHECK(diff > 1e-3 * norm);  // another barbule, another pattern
  const fs::path bad_dir = scratch("instance-bad");
  const auto bad = run("compare " + source("tests/cli/data/compare-tiny.yaml") + " --instance -1 --out " + bad_dir.string());
  CHECK(bad.status != 0);
  CHECK(!fs::exists(bad_dir));
}

TEST_CASE("plumage compare: a selection the config does not have is refused at its flag", "[cli][compare]") {
  const std::string config = source("tests/cli/data/compare-tiny.yaml");
  struct Case {
    std::string flags, expect;
  };
  for (const Case& c : {Case{"--only nosuch", "--only: " + config + " has no method named 'nosuch'"},
                        Case{"--reference nosuch", "--reference: " + config + " has no method named 'nosuch'"},
                        Case{"--wavelengths 500", "--wavelengths: " + config + " has no wavelength 500 nm"}}) {
    const fs::path out = scratch("selection");
    const auto r = run("compare " + config + " " + c.flags + " --out " + out.string());
    INFO(c.flags << ": " << r.output);
    CHECK(r.status == 2);
    CHECK_THAT(r.output, Catch::Contains(c.expect));
    CHECK_FALSE(fs::exists(out));
  }
}

TEST_CASE("plumage compare: config errors name file:line and field, nothing is written", "[cli][compare]") {
  const fs::path dir = scratch("errors");
  fs::create_directories(dir);
  const std::string species = source("configs/species/hummingbird.yaml");
  const std::string head = "comparison: bad\nspecies: " + species +
                           "\nsegment_um: 6\nwavelengths_nm: [500, 600]\nincident_deg: [[0, 0]]\n";
  struct Case {
    std::string name, body, expect;
  };
  const std::vector<Case> cases{
      {"unknown_key.yaml", "methods:\n  - {name: a, solver: approximate, geometri: exact}\n", ":7:"},
      {"bad_reference.yaml", "reference: nope\nmethods:\n  - {name: a, solver: approximate}\n", ":6:"},
      {"bad_solver.yaml", "methods:\n  - {name: a, solver: {type: approximat}}\n", "approximate"},
      {"bad_option.yaml", "methods:\n  - {name: a, solver: {type: approximate, currents: both}}\n", "currents"},
      // Recording the solver section for the times CSV must not mark its keys as read.
      {"unknown_option.yaml", "methods:\n  - {name: a, solver: {type: approximate, curents: reflected}}\n",
       "unknown key 'curents' (did you mean 'currents'?)"},
      {"duplicate.yaml", "methods:\n  - {name: a, solver: approximate}\n  - {name: a, solver: approximate}\n", ":8:"},
      {"bad_incident.yaml", "methods:\n  - {name: a, solver: approximate}\n", ":5:"},
      {"bad_override.yaml", "structure_overrides: {outline.thikness_um: 3}\nmethods:\n  - {name: a, solver: approximate}\n",
       ":6:"},
  };
  for (const auto& c : cases) {
    std::string text = head + c.body;
    if (c.name == "bad_incident.yaml") text = "comparison: bad\nspecies: " + species +
                                              "\nsegment_um: 6\nwavelengths_nm: [500, 600]\nincident_deg: [[95, 0]]\n" + c.body;
    const fs::path file = dir / c.name;
    std::ofstream(file) << text;
    const fs::path out = dir / (c.name + ".out");
    const auto r = run("compare " + file.string() + " --out " + out.string());
    INFO(c.name << ": " << r.output);
    CHECK(r.status == 2);
    CHECK_THAT(r.output, Catch::Contains(file.string()) && Catch::Contains(c.expect));
    CHECK_FALSE(fs::exists(out));
  }
  // Reduced layers of a crystal-type barbule: an error at the method's `geometry` line.
  const fs::path mallard = dir / "mallard_reduced.yaml";
  std::ofstream(mallard) << "comparison: bad\nspecies: " << source("configs/species/mallard.yaml")
                         << "\nsegment_um: 16\nwavelengths_nm: [500]\nincident_deg: [[0, 0]]\nmethods:\n"
                            "  - name: a\n    solver: {type: approximate}\n    reflection: {model: multilayer}\n"
                            "    geometry: reduced_layers\n";
  const fs::path out = dir / "mallard.out";
  const auto r = run("compare " + mallard.string() + " --out " + out.string());
  INFO(r.output);
  CHECK(r.status == 2);
  CHECK_THAT(r.output, Catch::Contains(mallard.string() + ":10:") && Catch::Contains("no layered model"));
  CHECK_FALSE(fs::exists(out));
}

TEST_CASE("plumage simulate --directions full", "[cli][compare]") {
  const fs::path dir = scratch("full");
  fs::create_directories(dir);
  // The approximate solver radiates only the reflected field upward: a clear error, no files.
  auto r = run("simulate " + source("configs/validation/keratin-cylinder.yaml") + " --lambda-nm 550 --instances 1 --out " +
               (dir / "a.ffs").string() + " --csv " + (dir / "a.csv").string() + " --directions full");
  CHECK(r.status == 2);
  CHECK_THAT(r.output, Catch::Contains("--directions full needs a full-wave solver"));
  CHECK_FALSE(fs::exists(dir / "a.ffs"));
  CHECK_FALSE(fs::exists(dir / "a.csv"));
  r = run("simulate " + source("configs/validation/keratin-cylinder.yaml") + " --out " + (dir / "b.ffs").string() +
          " --directions half");
  CHECK(r.status == 2);

#ifdef PLUMAGE_HAVE_BEM
  // A keratin cylinder (r = 250 nm) under a plane wave, solved by the bem plug-in: the CSV's
  // dsigma_dphi_nm against the exact series (B&H: dσ/dΦ = 2/(π k0) (|T_co|² + |T_cross|²)).
  const fs::path csv = dir / "cylinder.csv";
  r = run("simulate " + source("tests/cli/data/cylinder-bem.yaml") + " --lambda-nm 550 --theta-deg 0,30 --out " +
          (dir / "cylinder.ffs").string() + " --csv " + csv.string() + " --directions full");
  INFO(r.output);
  REQUIRE(r.status == 0);
  const auto rows = read_csv(csv);
  REQUIRE(rows.size() == 2u * 3 * 360);
  const double lambda_um = 0.55;
  const std::complex<double> m(1.532 + 5890.0 / (550.0 * 550.0), 0.0);  // keratin, paper Eq. 1
  for (double theta_deg : {0.0, 30.0}) {
    const double theta = theta_deg * M_PI / 180.0;
    double diff2[2] = {0, 0}, ref2[2] = {0, 0}, total[2] = {0, 0};
    for (int pol = 1; pol <= 2; ++pol) {
      const auto s = plumage::oracle::solve_homogeneous_bh(0.25, m, lambda_um, theta, pol);
      for (const auto& row : rows) {
        if (num(row, "theta_i_deg") != theta_deg || row.at("pol") != std::to_string(pol)) continue;
        const double phi_o = num(row, "phi_o_deg") * M_PI / 180.0;
        const double Phi = plumage::oracle::scattering_angle(phi_o, 0.0);
        const double exact_nm = 1000.0 * 2.0 / (M_PI * s.k0) * (std::norm(s.t_co(Phi)) + std::norm(s.t_cross(Phi)));
        const double got = num(row, "dsigma_dphi_nm");
        CHECK(num(row, "sigma_2d_nm") == Approx(2.0 * M_PI * got).epsilon(1e-7));
        diff2[pol - 1] += (got - exact_nm) * (got - exact_nm);
        ref2[pol - 1] += exact_nm * exact_nm;
        total[pol - 1] += got * M_PI / 180.0;
      }
      INFO("theta_i " << theta_deg << " deg, pol " << pol);
      WARN("bem keratin cylinder r = 250 nm, 550 nm, theta_i " << theta_deg << " deg, pol " << pol
           << ": dsigma/dphi relative L2 to the series " << std::sqrt(diff2[pol - 1] / ref2[pol - 1])
           << ", C_sca " << total[pol - 1] << " nm vs " << s.q_sca * 500.0 << " nm");
      CHECK(std::sqrt(diff2[pol - 1] / ref2[pol - 1]) < 1e-2);
      // Its integral over the circle is the scattering width C_sca = Q_sca · 2a.
      CHECK(total[pol - 1] == Approx(s.q_sca * 500.0).epsilon(1e-2));
    }
  }
#else
  WARN("bem plug-in not built: the full-circle far field against the exact series was not checked");
#endif
}

TEST_CASE("plumage simulate: a warning reaches stderr and the far-field set's header", "[cli][compare][warnings]") {
#ifdef PLUMAGE_HAVE_BEM
  // The 4 um keratin film slab (configs/validation/keratin-film-slab-bem.yaml) at 7 points per
  // wavelength, below the bem plug-in's 14 (plugins/bem/NOTES.md §6); its long straight edges are
  // meshed at the requested ppw (a validation circle's 5 nm polygon edges would not be). The run
  // completes and says so on stderr and in the file.
  const fs::path dir = scratch("warnings");
  fs::create_directories(dir);
  std::ifstream in(source("configs/validation/keratin-film-slab-bem.yaml"));
  std::string yaml((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto at = yaml.find("  type: bem");
  REQUIRE(at != std::string::npos);
  const fs::path config = dir / "coarse.yaml";
  const fs::path fine_config = dir / "fine.yaml";
  std::ofstream(config) << yaml.substr(0, at) << "  type: bem\n  points_per_wavelength: 7\n" << yaml.substr(at + 12);
  std::ofstream(fine_config) << yaml.substr(0, at) << "  type: bem\n  points_per_wavelength: 20\n" << yaml.substr(at + 12);
  const fs::path out = dir / "coarse.ffs";
  auto r = run("simulate " + config.string() + " --lambda-nm 550 --instances 1 --out " + out.string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.output, Catch::Contains("warning: ") && Catch::Contains("[bem.mesh_coarse]"));
  std::ifstream f(out, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  CHECK(bytes.find("\nwarnings=bem.mesh_coarse: ") != std::string::npos);
  // At 20 ppw nothing is raised and the header has no warnings line.
  r = run("simulate " + fine_config.string() + " --lambda-nm 550 --instances 1 --out " + out.string());
  REQUIRE(r.status == 0);
  CHECK(r.output.find("warning: ") == std::string::npos);
  std::ifstream g(out, std::ios::binary);
  const std::string clean((std::istreambuf_iterator<char>(g)), std::istreambuf_iterator<char>());
  CHECK(clean.find("\nwarnings=") == std::string::npos);
#else
  WARN("bem plug-in not built: the warning path through plumage simulate was not checked");
#endif
}

TEST_CASE("plumage simulate refuses a geometrically invalid instance and writes nothing", "[cli][compare]") {
  // The hummingbird generator at a 0.3 um outline is outside its valid range: platelets cross each
  // other and the outline. A full-wave solver would mesh that as given, so simulate must refuse it.
  const fs::path dir = scratch("invalid");
  fs::create_directories(dir);
  std::ifstream in(source("configs/species/hummingbird.yaml"));
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  const std::string key = "\n    width_um: 40";
  const auto at = yaml.find(key);
  REQUIRE(at != std::string::npos);
  yaml.replace(at, key.size(), "\n    width_um: 0.3");
  const std::string corner = "\n    corner_um: 1.0";  // corners must fit in the width
  const auto at_corner = yaml.find(corner);
  REQUIRE(at_corner != std::string::npos);
  yaml.replace(at_corner, corner.size(), "\n    corner_um: 0.03");
  const fs::path config = dir / "narrow.yaml";
  std::ofstream(config) << yaml;
  const fs::path out = dir / "narrow.ffs";
  const auto r = run("simulate " + config.string() + " --lambda-nm 550 --instances 1 --out " + out.string());
  INFO(r.output);
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Catch::Contains(config.string()) && Catch::Contains("instance 0 is geometrically invalid") &&
                           Catch::Contains("boundaries cross"));
  CHECK_FALSE(fs::exists(out));
  // The shipped width is valid: the same command succeeds.
  const auto ok = run("simulate " + source("configs/species/hummingbird.yaml") +
                      " --lambda-nm 550 --instances 1 --out " + (dir / "ok.ffs").string());
  INFO(ok.output);
  CHECK(ok.status == 0);
  CHECK(fs::exists(dir / "ok.ffs"));
}
