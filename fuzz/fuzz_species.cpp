// Species configs through load_species_config (what characterize/simulate/geometry/spectra call)
// for the file's default variant and then every declared variant, as `plumage check` does.
#include "fuzz_configs.hpp"
#include "plumage/species_config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace plumage::fuzz;
  const auto file = config_input("species");
  write_bytes(file, as_text(data, size));
  expect_typed_errors([&] { plumage::load_species_config(file, registry()); });
  expect_typed_errors([&] {
    const auto variants = plumage::species_variants(file);
    for (std::size_t i = 0; i < variants.size() && i < 8; ++i)
      expect_typed_errors([&] { plumage::load_species_config(file, registry(), variants[i]); });
  });
  return 0;
}
