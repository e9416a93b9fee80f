// `plumage fit` end to end (issue 25 part 3): the example spec (configs/fits/rockdove-cortex.yaml,
// a synthetic measurement made at cortex 595 nm, gap 500 nm) recovers its truth within 3 reported
// σ and writes every output; a bad spec is refused with exit 2, file:line:field, nothing written.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli_run.hpp"

namespace fs = std::filesystem;
using plumage::cli_test::Result;
using plumage::cli_test::run;

namespace {

const std::string kSuite = "plumage-test-fit-cli";
const std::string kSpec = std::string(PLUMAGE_SOURCE_DIR) + "/configs/fits/rockdove-cortex.yaml";

// value and sigma of `path` from fit.csv (path,value,sigma,...).
std::pair<double, double> fitted(const std::string& csv, const std::string& path) {
  std::istringstream in(csv);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(path + ",", 0) != 0) continue;
    std::istringstream fields(line.substr(path.size() + 1));
    std::string value, sigma;
    std::getline(fields, value, ',');
    std::getline(fields, sigma, ',');
    return {std::stod(value), std::stod(sigma)};
  }
  FAIL("no row " << path << " in fit.csv");
  return {};
}

}  // namespace

TEST_CASE("fit recovers the example's cortex and gap and writes its outputs", "[cli][fit]") {
  const fs::path out = plumage::cli_test::fresh_scratch_path(kSuite, "rockdove");
  const Result r = run("fit " + kSpec + " --out " + out.string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK(r.output.find("model evaluations") != std::string::npos);
  const std::string csv = plumage::cli_test::file_bytes(out / "fit.csv");
  const auto [cortex, cortex_sigma] = fitted(csv, "variants.forest.nominal_stack.layers.0.thickness_nm");
  const auto [gap, gap_sigma] = fitted(csv, "variants.forest.nominal_stack.layers.1.thickness_nm");
  CHECK(std::abs(cortex - 595.0) < 3.0 * cortex_sigma);
  CHECK(std::abs(gap - 500.0) < 3.0 * gap_sigma);
  CHECK(cortex_sigma > 0.01);
  CHECK(cortex_sigma < 10.0);
  CHECK(fs::file_size(out / "fit.png") > 1000);
  const std::string yaml = plumage::cli_test::file_bytes(out / "fitted.yaml");
  CHECK(yaml.find("variant: forest_fit") != std::string::npos);
  for (const char* name : {"fit.txt", "fit_starts.csv", "fit_spectrum.csv"}) CHECK(fs::exists(out / name));
  // The written variant is a species file `plumage check` accepts.
  const Result check = run("check " + (out / "fitted.yaml").string());
  INFO(check.output);
  CHECK(check.status == 0);
}

TEST_CASE("fit refuses a bad spec with file:line:field and writes nothing", "[cli][fit]") {
  const fs::path dir = plumage::cli_test::scratch_dir(kSuite);
  const fs::path spec = dir / "bad.yaml";
  std::ofstream(spec) << "model: nominal_stack\nconfig: " << PLUMAGE_SOURCE_DIR << "/configs/species/rockdove.yaml\n"
                      << "parameters:\n  - {path: nominal_stack.layers.9.thickness_nm, bounds: [1, 2]}\n"
                      << "target: {points: [{lambda_nm: 500, R: 0.1}, {lambda_nm: 600, R: 0.1}]}\n";
  const fs::path out = plumage::cli_test::fresh_scratch_path(kSuite, "bad-out");
  const Result r = run("fit " + spec.string() + " --out " + out.string());
  INFO(r.output);
  CHECK(r.status == 2);
  CHECK(r.output.find(spec.string() + ":4:") != std::string::npos);
  CHECK(r.output.find("parameters[0].path") != std::string::npos);
  CHECK(!fs::exists(out));
}
