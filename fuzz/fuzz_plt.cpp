// Reflection tables (.plt) through ReflectionTable::load (what `table query/plot` and the
// photonic_crystal reflection call).
#include "fuzz_common.hpp"
#include "plumage/reflection_table.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace plumage::fuzz;
  const auto file = scratch() / "fuzz-input.plt";
  write_bytes(file, as_text(data, size));
  expect_typed_errors([&] { plumage::ReflectionTable::load(file); });
  // The same bytes with their checksum made right (fuzz_common.hpp).
  const std::string fixed = with_fnv1a_trailer(as_text(data, size));
  if (!fixed.empty()) {
    write_bytes(file, fixed);
    expect_typed_errors([&] { plumage::ReflectionTable::load(file); });
  }
  return 0;
}
