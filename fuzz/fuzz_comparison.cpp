// Comparison configs (configs/compare/*.yaml) through load_comparison (what `compare` calls).
#include "fuzz_configs.hpp"
#include "plumage/comparison.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace plumage::fuzz;
  const auto file = config_input("compare");
  write_bytes(file, as_text(data, size));
  expect_typed_errors([&] { plumage::load_comparison(file, registry()); });
  return 0;
}
