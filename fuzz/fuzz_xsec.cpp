// Cross sections (.xsec, plumage-cross-section 1) through read_cross_section_text (what the
// xsec_file structure generator calls for every instance), then validate() on what was read, as
// `plumage geometry` and simulate check every instance before using it.
#include "fuzz_common.hpp"
#include "plumage/cross_section.hpp"
#include "plumage/cross_section_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace plumage::fuzz;
  const auto file = scratch() / "fuzz-input.xsec";
  write_bytes(file, as_text(data, size));
  expect_typed_errors([&] { (void)plumage::validate(plumage::read_cross_section_text(file)); });
  return 0;
}
