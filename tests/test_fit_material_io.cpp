// .plm round trip, checksum and error reporting (docs/formats.md "Feather material (.plm)").
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "plumage/error.hpp"
#include "plumage/feather_material.hpp"

using namespace plumage;

namespace {

FeatherMaterial sample_material() {
  FeatherMaterial m;
  m.label = "rockdove/forest";
  m.config_hash = "0123abcd";
  m.fidelity = "preview";
  m.sigma = 0.04;
  m.l0 = 0.0123;
  m.grid = 4;
  m.lambda_nm = {400, 406, 412};
  m.nodes.resize(3 * 25);
  for (std::size_t k = 0; k < m.nodes.size(); ++k) {
    for (int p = 0; p < kMaterialParameters; ++p) m.nodes[k].*kMaterialFields[p] = 0.001 * k + 0.17 * p + 1e-17 * k;  // pol_share (p = 6) a share, <= 2
  }
  m.noise.samples = 16;
  m.noise.lag1 = 0.93;
  for (int k = 0; k < 5 * 16; ++k) m.noise.functions.push_back(static_cast<float>(std::sin(0.7 * k)));
  return m;
}

std::filesystem::path temp_file(const char* name) {
  auto dir = std::filesystem::temp_directory_path() / "plumage-test-plm";
  std::filesystem::create_directories(dir);
  return dir / name;
}

}  // namespace

TEST_CASE("feather material file: exact round trip", "[material][fit-io]") {
  const FeatherMaterial m = sample_material();
  const auto file = temp_file("round.plm");
  write_feather_material(file, m);
  const FeatherMaterial r = read_feather_material(file);
  CHECK(r.label == m.label);
  CHECK(r.config_hash == m.config_hash);
  CHECK(r.fidelity == m.fidelity);
  CHECK(r.sigma == m.sigma);
  CHECK(r.l0 == m.l0);
  CHECK(r.grid == m.grid);
  CHECK(r.lambda_nm == m.lambda_nm);
  CHECK(r.bin_width_nm == m.bin_width_nm);
  REQUIRE(r.nodes.size() == m.nodes.size());
  for (std::size_t k = 0; k < m.nodes.size(); ++k)
    for (auto f : kMaterialFields) CHECK(r.nodes[k].*f == m.nodes[k].*f);
  CHECK(r.noise.samples == 16);
  CHECK(r.noise.lag1 == 0.93);
  CHECK(r.noise.functions == m.noise.functions);
}

TEST_CASE("feather material file: corruption and bad input name the file", "[material][fit-io]") {
  const auto file = temp_file("corrupt.plm");
  write_feather_material(file, sample_material());
  {
    std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(100);
    f.put('\x7f');
  }
  CHECK_THROWS_WITH(read_feather_material(file), Catch::Contains("corrupt.plm") && Catch::Contains("checksum"));
  const auto size = std::filesystem::file_size(file);
  std::filesystem::resize_file(file, size - 20);
  CHECK_THROWS_WITH(read_feather_material(file), Catch::Contains("corrupt.plm"));
  CHECK_THROWS_WITH(read_feather_material(temp_file("missing.plm")), Catch::Contains("missing.plm"));

  // A material inconsistent with its grid is refused and nothing is written.
  FeatherMaterial bad = sample_material();
  bad.nodes.pop_back();
  const auto target = temp_file("bad.plm");
  std::filesystem::remove(target);
  CHECK_THROWS_AS(write_feather_material(target, bad), Error);
  CHECK_FALSE(std::filesystem::exists(target));
}

TEST_CASE("feather material header: read alone, without the tables", "[material][fit-io]") {
  FeatherMaterial m = sample_material();
  m.warnings = "fit.two_lobes: raised while computing 1 of 3 work groups\n";
  m.key_text = "plumage material key 1\nlabel rockdove/forest\nspecies 0123456789abcdef\n";
  m.key = "fedcba9876543210";
  const auto file = temp_file("header.plm");
  write_feather_material(file, m);
  const FeatherMaterialHeader h = read_feather_material_header(file);
  CHECK(h.version == FeatherMaterial::kFormatVersion);
  CHECK(h.label == m.label);
  CHECK(h.config_hash == m.config_hash);
  CHECK(h.fidelity == m.fidelity);
  CHECK(h.warnings == m.warnings);
  CHECK(h.key == m.key);
  CHECK(h.key_text == m.key_text);
  CHECK(read_feather_material(file).key_text == m.key_text);
  CHECK(h.sigma == m.sigma);
  CHECK(h.l0 == m.l0);
  CHECK(h.bin_width_nm == m.bin_width_nm);
  CHECK(h.grid == m.grid);
  CHECK(h.lambda_nm == m.lambda_nm);
  // The header needs nothing after it: a file cut right after the wavelength list (its tables
  // and checksum gone) still gives its header, while the full read refuses it.
  const std::size_t header_bytes = 8 + 4 + (4 + m.label.size()) + (4 + m.config_hash.size()) + (4 + m.fidelity.size()) +
                                   (4 + m.warnings.size()) + (4 + m.key.size()) + (4 + m.key_text.size()) + 3 * 8 + 4 + 4 +
                                   8 * m.lambda_nm.size();
  std::filesystem::resize_file(file, header_bytes);
  CHECK(read_feather_material_header(file).lambda_nm == m.lambda_nm);
  CHECK_THROWS_WITH(read_feather_material(file), Catch::Contains("header.plm"));
  std::filesystem::resize_file(file, header_bytes - 1);
  CHECK_THROWS_WITH(read_feather_material_header(file), Catch::Contains("header.plm") && Catch::Contains("truncated"));
  CHECK_THROWS_WITH(read_feather_material_header(temp_file("missing.plm")), Catch::Contains("missing.plm"));
  std::ofstream(temp_file("text.plm")) << "not a material at all, but long enough to hold a header";
  CHECK_THROWS_WITH(read_feather_material_header(temp_file("text.plm")), Catch::Contains("bad magic"));
}
