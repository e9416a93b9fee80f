// Feather materials (.plm) through read_feather_material (what render/brdf call) and
// read_feather_material_header (what the material store compares).
#include "fuzz_common.hpp"
#include "plumage/feather_material.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace plumage::fuzz;
  const auto file = scratch() / "fuzz-input.plm";
  write_bytes(file, as_text(data, size));
  expect_typed_errors([&] { plumage::read_feather_material_header(file); });
  expect_typed_errors([&] { plumage::read_feather_material(file); });
  // The same bytes with their checksum made right (fuzz_common.hpp).
  const std::string fixed = with_fnv1a_trailer(as_text(data, size));
  if (!fixed.empty()) {
    write_bytes(file, fixed);
    expect_typed_errors([&] { plumage::read_feather_material_header(file); });
    expect_typed_errors([&] { plumage::read_feather_material(file); });
  }
  return 0;
}
