// FeatherLab's per-instance text files (docs/formats.md, "Cross sections from FeatherLab files")
// through parse_featherlab_instance, what the featherlab_files structure generator calls for
// every instance (it ends with validate()). The input holds the three files one after another,
// xyvals, info and melaninRatio, each ended by a line "%%" (a missing part is empty). Fixed
// options: the rock dove's four layers, keratin | air | granules of melanin in air | keratin,
// the melanin ratio on the third.
#include <string>
#include <string_view>

#include "fuzz_common.hpp"
#include "plumage/featherlab_section.hpp"

namespace {

// The part of `bytes` from `at` to the next line "%%" (or the end); `at` moves past it.
std::string next_part(std::string_view bytes, std::size_t& at) {
  if (at >= bytes.size()) return {};
  const std::string_view rest = bytes.substr(at);
  const std::size_t end = rest.find("\n%%\n");
  if (end == std::string_view::npos) {
    at = bytes.size();
    return std::string(rest);
  }
  at += end + 4;
  return std::string(rest.substr(0, end + 1));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace plumage::fuzz;
  static const plumage::FeatherLabImportOptions options = [] {
    plumage::FeatherLabImportOptions o;
    const plumage::Material granules =
        plumage::Material::mixture(plumage::Material::air(), plumage::Material::melanin(), 0.9);
    o.layers = {plumage::Material::keratin(), plumage::Material::air(), granules, plumage::Material::keratin()};
    o.melanin_ratio_layer = 2;
    return o;
  }();
  const std::string_view bytes = as_text(data, size);
  std::size_t at = 0;
  plumage::FeatherLabTexts t;
  t.xyvals = next_part(bytes, at);
  t.info = next_part(bytes, at);
  t.melanin_ratio = next_part(bytes, at);
  t.xyvals_name = "xyvals1.txt";
  t.info_name = "info1.txt";
  t.melanin_ratio_name = "melaninRatio1.txt";
  expect_typed_errors([&] { (void)plumage::parse_featherlab_instance(t, options); });
  return 0;
}
