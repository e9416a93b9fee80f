// Cross sections traced in SVG (docs/formats.md, "Cross sections from SVG") through
// read_svg_cross_section, what the svg_file structure generator calls for every instance, then
// validate() on the section, as every instance is checked before it is used. Fixed options: one
// user unit is 10 nm; ids starting "cortex" or a grey fill are keratin, ids starting "melanin"
// or a black fill melanin.
#include "fuzz_common.hpp"
#include "plumage/cross_section.hpp"
#include "plumage/cross_section_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace plumage::fuzz;
  static const plumage::SvgImportOptions options = [] {
    plumage::SvgImportOptions o;
    o.um_per_unit = 0.01;
    o.materials = {{"cortex", plumage::Material::keratin()}, {"melanin", plumage::Material::melanin()},
                   {"#808080", plumage::Material::keratin()}, {"#000000", plumage::Material::melanin()}};
    return o;
  }();
  const auto file = scratch() / "fuzz-input.svg";
  write_bytes(file, as_text(data, size));
  expect_typed_errors([&] { (void)plumage::validate(plumage::read_svg_cross_section(file, options)); });
  return 0;
}
