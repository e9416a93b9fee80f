// `plumage spectra --measured` end to end (issue 25): the rock dove's predicted spectra against a
// measured file written here; the comparison printed, the picture and the CSV's measured column
// written; a bad measurement refused with exit 2 and file:line before anything is computed.
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

const std::string kSuite = "plumage-test-spectra-cli";
const std::string kRockDove = std::string(PLUMAGE_SOURCE_DIR) + "/configs/species/rockdove.yaml";

fs::path write_file(const std::string& name, const std::string& text) {
  const fs::path file = plumage::cli_test::scratch_dir(kSuite) / name;
  std::ofstream(file) << text;
  return file;
}

// A measured-looking spectrum: a percent peak at 560 nm, semicolon-delimited with decimal commas.
std::string european_spectrum() {
  std::ostringstream text;
  text << "Sample: rock dove neck\nWavelength (nm);Reflectance (%)\n";
  for (int l = 380; l <= 760; l += 2) {
    std::string r = std::to_string(20.0 + 30.0 * std::exp(-std::pow((l - 560.0) / 40.0, 2)));
    r[r.find('.')] = ',';
    text << l << ';' << r << '\n';
  }
  return text.str();
}

}  // namespace

TEST_CASE("spectra --measured prints the comparison, draws it and adds it to the CSV", "[cli][spectra]") {
  const fs::path measured = write_file("dove.csv", european_spectrum());
  const fs::path png = plumage::cli_test::fresh_scratch_path(kSuite, "overlay.png");
  const fs::path csv = plumage::cli_test::fresh_scratch_path(kSuite, "overlay.csv");
  const Result r =
      run("spectra " + kRockDove + " --lambda-nm 400:700:10 --theta-deg 0 --measured " + measured.string() +
          " --measured-theta-deg 30 --plot " + png.string() + " --csv " + csv.string());
  INFO(r.output);
  REQUIRE(r.status == 0);
  CHECK(r.output.find("semicolon-delimited, decimal comma") != std::string::npos);
  CHECK(r.output.find("header says %") != std::string::npos);
  CHECK(r.output.find("theta 30.0 deg: peak predicted") != std::string::npos);
  CHECK(r.output.find("measured 560.0 nm") != std::string::npos);
  CHECK(r.output.find("RMS error") != std::string::npos);
  CHECK(fs::file_size(png) > 1000);
  const std::string table = plumage::cli_test::file_bytes(csv);
  CHECK(table.find("R,R_measured\n") != std::string::npos);
  // θ = 30° was added to the prediction for the measurement; at 560 nm the file says 50 %.
  CHECK(table.find(",30,560,") != std::string::npos);
  CHECK(table.find(",0.5\n") != std::string::npos);
}

TEST_CASE("spectra --measured refuses a bad file with exit 2 and file:line, writing nothing", "[cli][spectra]") {
  const fs::path measured = write_file("bad.csv", "nm,R\n400,0.1\n410,0.2\n405,0.3\n");
  const fs::path png = plumage::cli_test::fresh_scratch_path(kSuite, "bad.png");
  const Result r = run("spectra " + kRockDove + " --measured " + measured.string() + " --plot " + png.string());
  INFO(r.output);
  CHECK(r.status == 2);
  CHECK(r.output.find("bad.csv:4: wavelengths not monotonic") != std::string::npos);
  CHECK_FALSE(fs::exists(png));
  const Result none = run("spectra " + kRockDove + " --measured " + (measured.string() + ".missing"));
  CHECK(none.status == 2);
  CHECK(none.output.find("bad.csv.missing") != std::string::npos);
  // The measurement is an input: --csv may not overwrite it; an angle outside [0, 90] is refused.
  const fs::path good = write_file("good.csv", "400,0.1\n500,0.2\n600,0.3\n");
  const Result overwrite = run("spectra " + kRockDove + " --measured " + good.string() + " --csv " + good.string());
  CHECK(overwrite.status == 2);
  CHECK(plumage::cli_test::file_bytes(good) == "400,0.1\n500,0.2\n600,0.3\n");
  const Result angle = run("spectra " + kRockDove + " --measured " + good.string() + " --measured-theta-deg 95");
  CHECK(angle.status == 2);
  CHECK(angle.output.find("[0, 90]") != std::string::npos);
}
