// Findings of the fuzz harnesses (fuzz/, issue 23) as library cases: each input of
// fuzz/regressions is also replayed by the ctest smoke of its harness; here the refusal it must
// get is asserted (type and message).
#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>
#include <string>

#include "plumage/characterize.hpp"
#include "plumage/characterize_records.hpp"

namespace {

std::string seed_shard() {
  std::ifstream in(std::string(PLUMAGE_SOURCE_DIR) + "/fuzz/corpus/journal/rockdove-grid2-part2.shard", std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST_CASE("fuzz finding: a shard header with a non-integer count is refused naming the field", "[fuzz][characterize]") {
  const plumage::JournalContents j = plumage::parse_journal(seed_shard(), "seed.shard");
  REQUIRE(j.fingerprint.find(" pattern=400 ") != std::string::npos);
  // The header as written reads back (the seed is valid).
  CHECK_NOTHROW(plumage::CharacterizeSettings::from_fingerprint(j.fingerprint, j.config_hash, j.inputs));
  for (const std::string& bad : {"]00", "", "4x", "99999999999"}) {
    std::string line = j.fingerprint;
    line.replace(line.find(" pattern=400 ") + 9, 3, bad);
    INFO(line);
    try {
      plumage::CharacterizeSettings::from_fingerprint(line, j.config_hash, j.inputs);
      FAIL("accepted");
    } catch (const plumage::Error& e) {
      CHECK(std::string(e.what()).find("field pattern") != std::string::npos);
    }
  }
}
