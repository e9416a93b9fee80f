// Crystal configs (configs/crystals/*.yaml) through load_crystal_cell (what `table build` calls).
#include "fuzz_configs.hpp"
#include "plumage/crystal_cell.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace plumage::fuzz;
  const auto file = config_input("crystals");
  write_bytes(file, as_text(data, size));
  expect_typed_errors([&] { plumage::load_crystal_cell(file); });
  return 0;
}
