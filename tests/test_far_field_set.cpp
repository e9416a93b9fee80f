// FarFieldSet files: round trip, and corruption is detected rather than read as data.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "plumage/error.hpp"
#include "plumage/far_field_set.hpp"

using namespace plumage;
namespace fs = std::filesystem;

namespace {
FarFieldSet sample() {
  FarFieldSet set;
  set.metadata = {{"species", "test"}, {"solver", "approximate"}};
  FarFieldUnit u;
  u.lambda_nm = 532.0;
  u.nominal = {0.1, -0.2};
  u.pattern_count = 2;
  for (int n = 0; n < 3; ++n) {
    FarField ff;
    ff.lambda_nm = 532.0;
    ff.incident = {0.1, -0.2 + 0.01 * n};
    ff.phi_o_rad = {-0.5, 0.5, 0.7};
    ff.incident_power = {1.5 + n, 1.5 + n};
    for (int p = 0; p < 2; ++p) {
      for (int j = 0; j < 3; ++j) ff.field[p].push_back({Complex(n, j), Complex(p, -j), Complex(0.25, 0.5)});
    }
    u.instances.push_back(ff);
  }
  set.units.push_back(u);
  return set;
}
}  // namespace

TEST_CASE("far-field sets round-trip and refuse corrupt files", "[files]") {
  const fs::path dir = fs::temp_directory_path() / "plumage-test-ffs";
  fs::create_directories(dir);
  const fs::path file = dir / "a.ffs";
  write_far_field_set(sample(), file);
  const FarFieldSet back = read_far_field_set(file);
  REQUIRE(back.units.size() == 1);
  CHECK(back.metadata.at("species") == "test");
  const auto& u = back.units[0];
  CHECK(u.pattern_count == 2);
  REQUIRE(u.instances.size() == 3);
  CHECK(u.instances[2].incident.phi_rad == Approx(-0.18));
  CHECK(u.instances[2].field[1][2][1] == Complex(1.0f, -2.0f));
  CHECK(u.instances[1].incident_power[0] == 2.5);
  // Flip one byte in the middle: the checksum catches it.
  {
    std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(fs::file_size(file) / 2));
    f.put('\x7f');
  }
  CHECK_THROWS_WITH(read_far_field_set(file), Catch::Contains("checksum mismatch"));
  // Truncation too.
  fs::resize_file(file, fs::file_size(file) - 20);
  CHECK_THROWS_AS(read_far_field_set(file), Error);
  std::ofstream(dir / "b.ffs") << "not a far-field set at all";
  CHECK_THROWS_WITH(read_far_field_set(dir / "b.ffs"), Catch::Contains("bad magic"));
}
