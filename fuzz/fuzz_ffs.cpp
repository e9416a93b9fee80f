// Far-field sets (.ffs, written by `plumage simulate`) through read_far_field_set, the format's
// one reader.
#include "fuzz_common.hpp"
#include "plumage/far_field_set.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace plumage::fuzz;
  const auto file = scratch() / "fuzz-input.ffs";
  write_bytes(file, as_text(data, size));
  expect_typed_errors([&] { plumage::read_far_field_set(file); });
  // The same bytes with their checksum made right (fuzz_common.hpp).
  const std::string fixed = with_fnv1a_trailer(as_text(data, size));
  if (!fixed.empty()) {
    write_bytes(file, fixed);
    expect_typed_errors([&] { plumage::read_far_field_set(file); });
  }
  return 0;
}
