// Measured spectra (issue 25): the reader's dialects (delimiters, decimal comma, percent, µm,
// spectrometer markers, angle columns, samples), its refusals with file:line, and compare_spectra
// on an analytic pair.
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "plumage/input_file.hpp"
#include "plumage/measured_spectrum.hpp"

using namespace plumage;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

fs::path write_spectrum(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / ("plumage_measured_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const fs::path file = dir / name;
  std::ofstream(file, std::ios::binary) << text;
  return file;
}

bool has_note(const MeasuredSpectrum& m, const std::string& word) {
  for (const auto& n : m.notes)
    if (n.find(word) != std::string::npos) return true;
  return false;
}

// The message of the InputFileError read_measured_spectrum throws ("" if none).
std::string refusal(const std::string& name, const std::string& text) {
  const fs::path file = write_spectrum(name, text);
  try {
    read_measured_spectrum(file);
  } catch (const InputFileError& e) {
    return e.what();
  }
  return "";
}

double gaussian(double l, double centre) { return 0.1 + 0.5 * std::exp(-0.5 * std::pow((l - centre) / 30.0, 2)); }

}  // namespace

TEST_CASE("measured spectrum: comma CSV with a header, fractions", "[measured]") {
  const auto m = read_measured_spectrum(write_spectrum("a.csv", "wavelength_nm,R\n400,0.1\n410,0.2\n420,0.3\n"));
  REQUIRE(m.curves.size() == 1);
  CHECK(m.curves[0].label == "R");
  CHECK(m.curves[0].lambda_nm == std::vector<double>{400, 410, 420});
  CHECK(m.curves[0].reflectance == std::vector<double>{0.1, 0.2, 0.3});
  CHECK_FALSE(m.curves[0].theta_deg);
  CHECK(has_note(m, "comma-delimited"));
  CHECK(has_note(m, "fraction"));
}

TEST_CASE("measured spectrum: semicolons with decimal commas, percent from the header", "[measured]") {
  const auto m = read_measured_spectrum(
      write_spectrum("b.csv", "Messung 3\nWellenlänge [nm];Reflexion [%]\n400,5;10,0\n401,5;1,25\n402,5;0,5\n"));
  REQUIRE(m.curves.size() == 1);
  CHECK(m.curves[0].lambda_nm == std::vector<double>{400.5, 401.5, 402.5});
  CHECK(m.curves[0].reflectance[0] == Approx(0.1));
  CHECK(m.curves[0].reflectance[2] == Approx(0.005));  // percent: the header says so
  CHECK(has_note(m, "decimal comma"));
  CHECK(has_note(m, "header says %"));
}

TEST_CASE("measured spectrum: tab-separated, percent from the values, CRLF, decreasing", "[measured]") {
  const auto m = read_measured_spectrum(write_spectrum("c.tsv", "420\t30\r\n410\t20\r\n400\t10\r\n"));
  REQUIRE(m.curves.size() == 1);
  CHECK(m.curves[0].lambda_nm == std::vector<double>{400, 410, 420});  // reversed
  CHECK(m.curves[0].reflectance == std::vector<double>{0.1, 0.2, 0.3});
  CHECK(has_note(m, "values above 1.5"));
  CHECK(has_note(m, "tab-delimited"));
}

TEST_CASE("measured spectrum: Ocean Optics export with markers", "[measured]") {
  const std::string text =
      "Data from refl.txt Node\n\nDate: Mon Nov 30 10:11:12 CET 2026\nUser: lab\nIntegration Time (sec): 1.0E-1\n"
      "Number of Pixels in Spectrum: 4\n2048\n>>>>>Begin Spectral Data<<<<<\n"
      "350.12\t12.5\n350.50\t13.0\n350.88\t14.5\n351.26\t15.0\n>>>>>End Spectral Data<<<<<\n";
  const auto m = read_measured_spectrum(write_spectrum("d.txt", text));
  REQUIRE(m.curves.size() == 1);
  CHECK(m.curves[0].lambda_nm.size() == 4);
  CHECK(m.curves[0].lambda_nm[1] == 350.50);
  CHECK(m.curves[0].reflectance[3] == Approx(0.15));
  CHECK(has_note(m, "from line 9"));
}

TEST_CASE("measured spectrum: a names line over a units line, counts beside the reflectance", "[measured]") {
  // An Avantes-like export: the reflectance column is taken over the raw counts before it.
  const std::string text =
      "AvaSoft 8\nWave ;Sample ;Dark ;Reference;Reflectance\n[nm] ;[counts] ;[counts] ;[counts] ;[%]\n"
      "400;1200;100;2300;50\n401;1300;100;2400;52,5\n402;1400;100;2500;55\n";
  const auto m = read_measured_spectrum(write_spectrum("k.csv", text));
  REQUIRE(m.curves.size() == 1);
  CHECK(m.curves[0].label == "Reflectance [%]");
  CHECK(m.curves[0].reflectance == std::vector<double>{0.5, 0.525, 0.55});
  CHECK(has_note(m, "decimal comma"));  // from the second data row: the first has no comma
  CHECK(has_note(m, "4 reflectance columns"));
  CHECK(read_measured_spectrum(write_spectrum("k.csv", text), {0}).curves[0].label == "Sample [counts]");
}

TEST_CASE("measured spectrum: a UTF-8 byte-order mark before the first data row", "[measured]") {
  const auto m = read_measured_spectrum(write_spectrum("l.csv",
                                                       "\xEF\xBB\xBF"
                                                       "400,0.1\n410,0.2\n420,0.3\n"));
  REQUIRE(m.curves.size() == 1);
  CHECK(m.curves[0].lambda_nm.size() == 3);
  CHECK(has_note(m, "from line 1"));
}

TEST_CASE("measured spectrum: a lone number before the data is header", "[measured]") {
  const auto m = read_measured_spectrum(write_spectrum("m.txt", "Pixels\n2048\n400 0.1\n410 0.2\n420 0.3\n"));
  REQUIRE(m.curves.size() == 1);
  CHECK(m.curves[0].lambda_nm.size() == 3);
  CHECK(has_note(m, "from line 3"));
}

TEST_CASE("measured spectrum: micrometres, whitespace, '#' comments", "[measured]") {
  const auto m =
      read_measured_spectrum(write_spectrum("e.dat", "# um  R\n0.40  0.2\n# a note\n0.45   0.3\n0.50 0.4\n"));
  REQUIRE(m.curves.size() == 1);
  CHECK(m.curves[0].lambda_nm[0] == Approx(400));
  CHECK(m.curves[0].lambda_nm[2] == Approx(500));
  CHECK(has_note(m, "micrometres"));
  CHECK(has_note(m, "whitespace"));
}

TEST_CASE("measured spectrum: angles in the column headers, an angle column, samples", "[measured]") {
  SECTION("angle headers: one curve per column") {
    const auto m = read_measured_spectrum(
        write_spectrum("f.csv", "lambda_nm,R_0deg,30°,theta=45\n400,0.1,0.2,0.3\n410,0.1,0.2,0.3\n420,0.1,0.2,0.3\n"));
    REQUIRE(m.curves.size() == 3);
    CHECK(*m.curves[0].theta_deg == 0);
    CHECK(*m.curves[1].theta_deg == 30);
    CHECK(*m.curves[2].theta_deg == 45);
    CHECK(m.curves[2].reflectance[0] == 0.3);
    CHECK(measured_curve_at(m, 30.0) == &m.curves[1]);
    CHECK(measured_curve_at(m, 20.0) == nullptr);
    const auto only = with_measurement_angle(m, 45.0);
    REQUIRE(only.curves.size() == 1);
    CHECK(only.curves[0].label == "theta=45");
    CHECK_THROWS_AS(with_measurement_angle(m, 20.0), InputFileError);
  }
  SECTION("an angle column: one curve per angle") {
    const auto m = read_measured_spectrum(write_spectrum(
        "g.csv", "theta_deg,lambda_nm,R\n0,400,0.1\n0,410,0.2\n0,420,0.3\n60,400,0.4\n60,410,0.5\n60,420,0.6\n"));
    REQUIRE(m.curves.size() == 2);
    CHECK(*m.curves[1].theta_deg == 60);
    CHECK(m.curves[1].reflectance == std::vector<double>{0.4, 0.5, 0.6});
  }
  SECTION("several samples: the first, or the one asked for") {
    const std::string text = "nm,sample A,sample B\n400,0.1,0.5\n410,0.2,0.6\n420,0.3,0.7\n";
    const auto first = read_measured_spectrum(write_spectrum("h.csv", text));
    REQUIRE(first.curves.size() == 1);
    CHECK(first.curves[0].label == "sample A");
    CHECK(has_note(first, "2 reflectance columns"));
    const auto second = read_measured_spectrum(write_spectrum("h.csv", text), {1});
    CHECK(second.curves[0].reflectance[0] == 0.5);
    CHECK_THROWS_AS(read_measured_spectrum(write_spectrum("h.csv", text), {2}), InputFileError);
  }
  SECTION("no angle: normal incidence assumed, or the one given") {
    const auto m = read_measured_spectrum(write_spectrum("i.csv", "400,0.1\n410,0.2\n420,0.3\n"));
    CHECK(*with_measurement_angle(m, std::nullopt).curves[0].theta_deg == 0.0);
    CHECK(has_note(with_measurement_angle(m, std::nullopt), "normal incidence"));
    CHECK(*with_measurement_angle(m, 30.0).curves[0].theta_deg == 30.0);
  }
}

TEST_CASE("measured spectrum: bad input is refused with file:line", "[measured]") {
  CHECK_THAT(refusal("j1.csv", "nm,R\n400,0.1\n410,0.2\n405,0.3\n420,0.4\n"),
             Contains("j1.csv:4: wavelengths not monotonic"));
  CHECK_THAT(refusal("j2.csv", "nm,R\n400,0.1\n410,-0.2\n420,0.3\n"), Contains("j2.csv:3: negative reflectance"));
  CHECK_THAT(refusal("j3.csv", "nm,R\n400,0.1\n410,0.2\n"), Contains("j3.csv:2: R: 2 points (at least 3"));
  CHECK_THAT(refusal("j4.csv", "just words\nand more words\n"), Contains("j4.csv: no numeric data"));
  CHECK_THAT(refusal("j5.csv", ""), Contains("no numeric data"));
  CHECK_THAT(refusal("j6.csv", "400,0.1\n410,0.2\n420\n430,0.4\n"),
             Contains("j6.csv:3: 1 fields where the data has 2"));
  CHECK_THAT(refusal("j7.csv", "400,0.1\n410,oops\n420,0.3\n"), Contains("j7.csv:2: not a row of numbers"));
  CHECK_THAT(refusal("j8.csv", "400,0.1\n410,nan\n420,0.3\n"), Contains("j8.csv:2: reflectance is not finite"));
  CHECK_THAT(refusal("j9.csv", "400\n410\n420\n"), Contains("j9.csv:1: one column"));
  CHECK_THAT(refusal("j10.csv", "0,0.1\n410,0.2\n420,0.3\n"), Contains("j10.csv:1: wavelength"));
  std::string wide = "400";
  for (int c = 0; c < 1000; ++c) wide += ",0.1";
  CHECK_THAT(refusal("j11.csv", wide + "\n"), Contains("j11.csv:1: 1001 columns (at most 1000)"));
  CHECK_THAT(refusal("j12.csv", "theta,nm,R\n0,400,0.1\n0,410,0.2\n95,400,0.3\n"), Contains("j12.csv:4: angle"));
  CHECK_THROWS_AS(read_measured_spectrum(fs::temp_directory_path() / "plumage_no_such_spectrum.csv"), InputFileError);
  CHECK_THROWS_AS(read_measured_spectrum(fs::temp_directory_path()), InputFileError);  // a directory
}

TEST_CASE("compare_spectra: a Gaussian against itself shifted by 7 nm", "[measured]") {
  std::vector<double> lambda, r;
  for (int i = 0; i <= 600; ++i) {  // predicted: 300..900 nm every 1 nm, peak at 550.3 (between samples)
    lambda.push_back(300.0 + i);
    r.push_back(gaussian(lambda.back(), 550.3));
  }
  MeasuredCurve measured{"shifted", 0.0, {}, {}};
  for (int j = 0; j <= 1400; ++j) {  // measured: 250..950 every 0.5 nm, peak at 557.3
    measured.lambda_nm.push_back(250.0 + 0.5 * j);
    measured.reflectance.push_back(gaussian(measured.lambda_nm.back(), 557.3));
  }
  const SpectrumComparison c = compare_spectra(lambda, r, measured);
  CHECK(c.predicted_peak_nm == Approx(550.3).margin(0.05));
  CHECK(c.measured_peak_nm == Approx(557.3).margin(0.05));
  CHECK(c.peak_difference_nm == Approx(7.0).margin(0.1));
  CHECK(c.points == 601);
  CHECK(c.common_from_nm == 300.0);
  CHECK(c.common_to_nm == 900.0);
  // ∫ (g(x) − g(x − d))² dx = 2 A² σ √π (1 − exp(−d²/4σ²)) with A = 0.5, σ = 30, d = 7; the
  // tails beyond 300..900 nm are negligible; the mean over 601 points 1 nm apart.
  const double integral = 2 * 0.25 * 30.0 * std::sqrt(M_PI) * (1 - std::exp(-49.0 / (4 * 900.0)));
  CHECK(c.rms_error == Approx(std::sqrt(integral / 601.0)).epsilon(1e-3));
  CHECK(c.correlation > 0.97);
  CHECK(c.correlation < 1.0);

  // No common range → refused; the same curve → zero error, correlation 1.
  MeasuredCurve far{"far", 0.0, {1000, 1010, 1020}, {0.1, 0.2, 0.3}};
  CHECK_THROWS_AS(compare_spectra(lambda, r, far), Error);
  MeasuredCurve same{"same", 0.0, lambda, r};
  const auto s = compare_spectra(lambda, r, same);
  CHECK(s.rms_error == 0.0);
  CHECK(s.correlation == Approx(1.0));
  CHECK(s.peak_difference_nm == 0.0);
}
