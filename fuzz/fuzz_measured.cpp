// Measured reflectance spectra (CSV/TSV/spectrometer text, measured_spectrum.hpp) through
// read_measured_spectrum, what `plumage spectra --measured FILE` reads before any computation.
#include "fuzz_common.hpp"
#include "plumage/measured_spectrum.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace plumage::fuzz;
  const auto file = scratch() / "fuzz-input.csv";
  write_bytes(file, as_text(data, size));
  expect_typed_errors([&] { (void)plumage::read_measured_spectrum(file); });
  return 0;
}
