// Measured reflectance spectra (issue 25): the reader of CSV/TSV files and spectrometer text
// exports, and the comparison of a predicted spectrum with a measured one (peak position, RMS
// error, correlation). The formats accepted are described in docs/formats.md.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace plumage {

// One measured curve: reflectance (a fraction, 0..1 for a white-standard-referenced measurement)
// against wavelength (nm, strictly increasing), at one angle of incidence when the file says which.
struct MeasuredCurve {
  std::string label;                // the column header ("R_30deg"), or "column 2" without one
  std::optional<double> theta_deg;  // from an angle column or the column header; none if unknown
  std::vector<double> lambda_nm;
  std::vector<double> reflectance;
};

struct MeasuredSpectrum {
  std::filesystem::path file;
  std::vector<MeasuredCurve> curves;  // one per angle, or the one sample chosen
  // What the reader decided, for the user: delimiter, percent or fraction, µm converted, the
  // column taken when there were several samples.
  std::vector<std::string> notes;
};

struct MeasuredSpectrumOptions {
  // Several reflectance columns whose headers name no angle are several samples: this one is
  // taken (0 = the first reflectance column); by default the one whose header names reflectance
  // ("refl") if exactly one does, else the first.
  std::optional<std::size_t> sample_column;
};

// Sanity limits of the reader (docs/architecture.md, "Readers"): a text spectrum is at most
// 64 MiB, 1 000 000 data rows and 1 000 columns; a curve needs at least 3 points.
inline constexpr std::uintmax_t kMaxMeasuredSpectrumBytes = std::uintmax_t{64} << 20;
inline constexpr std::size_t kMaxMeasuredSpectrumRows = 1'000'000;
inline constexpr std::size_t kMaxMeasuredSpectrumColumns = 1'000;
inline constexpr std::size_t kMinMeasuredSpectrumPoints = 3;

// Reads a measured spectrum. Accepts header and comment lines ('#' lines, any non-numeric lines
// before the data, Ocean Optics ">>>>>Begin Spectral Data<<<<<" / ">>>>>End..." markers), comma,
// semicolon, tab or whitespace delimiters (a decimal comma with ';', tab or whitespace), a names
// line over a units line, a UTF-8 byte-order mark, percent
// or fraction (a '%' / "percent" header, else any value > 1.5 → percent), nm or µm (all
// wavelengths < 10 → µm), an angle column (theta, angle, AOI: one curve per angle) or angle
// column headers ("R_0deg", "30°", "theta=45": one curve per column); a decreasing wavelength
// column is reversed. Throws InputFileError naming file:line and what is wrong: no numeric data,
// a field that is not a number, a row with another field count, wavelengths not monotonic or out
// of range, negative or non-finite reflectance, too few points, a size limit exceeded.
MeasuredSpectrum read_measured_spectrum(const std::filesystem::path& file, const MeasuredSpectrumOptions& options = {});

// The measurement's angles resolved for a comparison: curves without an angle get `theta_deg`
// (normal incidence, 0°, when not given; noted); when the curves have angles and `theta_deg` is
// given, only the curve at that angle is kept (InputFileError if there is none).
MeasuredSpectrum with_measurement_angle(MeasuredSpectrum measured, std::optional<double> theta_deg);

// The measured curve at `theta_deg` (within 1e-6°), or nullptr.
const MeasuredCurve* measured_curve_at(const MeasuredSpectrum& measured, double theta_deg);

struct SpectrumComparison {
  // Peak positions (nm): the largest sample inside the common range, refined by the parabola
  // through it and its two neighbours (the sample itself at the range's ends).
  double predicted_peak_nm = 0.0;
  double measured_peak_nm = 0.0;
  double peak_difference_nm = 0.0;  // measured − predicted
  // Over the predicted wavelengths inside the common range, the measured curve resampled onto
  // them by linear interpolation: root-mean-square of (measured − predicted) reflectance
  // (fraction) and the Pearson correlation of the two (0 when either is constant).
  double rms_error = 0.0;
  double correlation = 0.0;
  double common_from_nm = 0.0, common_to_nm = 0.0;
  std::size_t points = 0;  // predicted wavelengths compared
};

// Compares a predicted spectrum (strictly increasing λ) with a measured curve. Throws Error when
// the two share fewer than 3 predicted wavelengths.
SpectrumComparison compare_spectra(const std::vector<double>& predicted_lambda_nm,
                                   const std::vector<double>& predicted_reflectance, const MeasuredCurve& measured);

// The measured curve linearly interpolated at `lambda_nm`; none outside its range.
std::optional<double> measured_reflectance_at(const MeasuredCurve& measured, double lambda_nm);

}  // namespace plumage
