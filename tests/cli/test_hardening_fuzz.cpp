// Findings of the fuzz harnesses (fuzz/, issue 23) through the command: a shard whose header
// parses as a journal but carries a damaged settings field (fuzz/regressions/merge) is bad
// input of that shard: exit 2, the file and the field named, nothing written.
#include <catch2/catch.hpp>

#include "cli_run.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

TEST_CASE("merge: a shard header with a damaged integer field is refused naming the file and field", "[hardening-fuzz]") {
  const fs::path dir = plumage::cli_test::fresh_scratch_path("plumage-test-hardening-fuzz", "merge");
  fs::create_directories(dir);
  std::ifstream in(std::string(PLUMAGE_SOURCE_DIR) + "/fuzz/corpus/journal/rockdove-grid2-part2.shard", std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  std::string bytes = s.str();
  const auto at = bytes.find(" pattern=400 ");
  REQUIRE(at != std::string::npos);
  bytes.replace(at + 9, 3, "]00");
  const fs::path shard = dir / "damaged.shard", out = dir / "out.plm";
  std::ofstream(shard, std::ios::binary) << bytes;
  const auto r = plumage::cli_test::run("merge " + shard.string() + " --out " + out.string());
  INFO(r.output);
  CHECK(r.status == 2);
  CHECK(r.output.find(shard.string()) != std::string::npos);
  CHECK(r.output.find("field pattern") != std::string::npos);
  CHECK(!fs::exists(out));
}
