// Scene configs (configs/scenes/*.yaml) through load_scene_config (what `render` calls).
#include "fuzz_configs.hpp"
#include "plumage/scene_config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace plumage::fuzz;
  const auto file = config_input("scenes");
  write_bytes(file, as_text(data, size));
  expect_typed_errors([&] { plumage::load_scene_config(file); });
  return 0;
}
