// Readers refuse damaged or wrong input files (issue 23): files whose checksum was recomputed
// after damage (so only content validation can catch it), forged sizes (refused at once, before
// anything of their size is allocated), inputs that are not regular files (refused with the path
// named, never blocking), and journals with one damaged record (skipped alone).
#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "plumage/characterize_records.hpp"
#include "plumage/checksum.hpp"
#include "plumage/far_field_set.hpp"
#include "plumage/feather_material.hpp"
#include "plumage/input_file.hpp"
#include "plumage/reflection_table.hpp"

using namespace plumage;
namespace fs = std::filesystem;

namespace {

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "plumage-test-reader-hardening" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string bytes_of(const fs::path& f) {
  std::ifstream in(f, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Writes `data` with its trailing FNV-1a checksum recomputed (the project's own function), so
// that the damage passes the checksum.
void write_resealed(const fs::path& f, std::string data) {
  const std::uint64_t sum = fnv1a(std::string_view(data).substr(0, data.size() - 8));
  std::memcpy(data.data() + data.size() - 8, &sum, 8);
  std::ofstream(f, std::ios::binary | std::ios::trunc) << data;
}

template <class T>
std::string raw(T v) {
  return std::string(reinterpret_cast<const char*>(&v), sizeof v);
}

// Replaces the only occurrence of `from` in `data` by `to` (same size).
void replace_once(std::string& data, const std::string& from, const std::string& to) {
  const auto at = data.find(from);
  REQUIRE(at != std::string::npos);
  REQUIRE(data.find(from, at + 1) == std::string::npos);
  data.replace(at, from.size(), to);
}

FeatherMaterial material() {
  FeatherMaterial m;
  m.label = "rockdove/forest";
  m.fidelity = "preview";
  m.sigma = 0.04;
  m.l0 = 0.0123;
  m.bin_width_nm = 6;
  m.grid = 2;
  m.lambda_nm = {400, 406, 412};
  m.nodes.resize(3 * 9);
  for (std::size_t k = 0; k < m.nodes.size(); ++k) m.nodes[k].m_eff = 0.2 + 0.001 * static_cast<double>(k);
  m.nodes[5].phi_sta = 0.123456789;  // a unique value to find in the bytes
  m.noise.samples = 8;
  m.noise.lag1 = 0.4375;
  for (int k = 0; k < 2 * 8; ++k) m.noise.functions.push_back(0.01f * static_cast<float>(k));
  m.noise.functions[11] = 0.4242f;
  return m;
}

// Runs `read` on a file made from the valid `good` bytes by `damage`, resealed, and expects an
// InputFileError naming the file and containing `words`.
template <class Read>
void expect_refused(const fs::path& file, const std::string& good, void (*damage)(std::string&), Read read,
                    const std::vector<std::string>& words) {
  std::string data = good;
  damage(data);
  write_resealed(file, data);
  const auto t0 = std::chrono::steady_clock::now();
  try {
    read(file);
    FAIL("accepted a damaged file");
  } catch (const InputFileError& e) {
    INFO(e.what());
    CHECK(e.file() == file.string());
    for (const auto& w : words) CHECK(std::string(e.what()).find(w) != std::string::npos);
  }
  CHECK(std::chrono::steady_clock::now() - t0 < std::chrono::seconds(2));  // refused at once
}

const double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

TEST_CASE("reader hardening: .plm content is validated after the checksum", "[reader-hardening]") {
  const fs::path dir = scratch("plm");
  const fs::path good_file = dir / "good.plm", file = dir / "bad.plm";
  write_feather_material(good_file, material());
  const std::string good = bytes_of(good_file);
  REQUIRE(read_feather_material(good_file).nodes[5].phi_sta == 0.123456789);  // valid files still read
  const auto read = [](const fs::path& f) { (void)read_feather_material(f); };
  expect_refused(file, good, [](std::string& d) { replace_once(d, raw(0.123456789), raw(kNaN)); }, read,
                 {"phi_sta", "node 5", "nan"});
  expect_refused(file, good, [](std::string& d) { replace_once(d, raw(0.123456789), raw(1e9)); }, read,
                 {"phi_sta", "expected in"});
  expect_refused(file, good, [](std::string& d) { replace_once(d, raw(0.4242f), raw(std::numeric_limits<float>::quiet_NaN())); },
                 read, {"noise function 1, sample 3", "not finite"});
  expect_refused(file, good, [](std::string& d) { replace_once(d, raw(406.0), raw(399.0)); }, read,
                 {"lambda_nm[1]", "strictly increasing"});
  expect_refused(file, good, [](std::string& d) { replace_once(d, raw(412.0), raw(kNaN)); }, read, {"lambda_nm[2]"});
  expect_refused(file, good, [](std::string& d) { replace_once(d, raw(0.04), raw(-1.0)); }, read, {"sigma"});
  expect_refused(file, good, [](std::string& d) { replace_once(d, raw(0.4375), raw(3.0)); }, read, {"lag1"});
  // Forged sizes: wavelength bins (after grid 2) and the noise function count, refused at once.
  expect_refused(file, good, [](std::string& d) { replace_once(d, raw(std::int32_t{2}) + raw(std::uint32_t{3}), raw(std::int32_t{2}) + raw(std::uint32_t{99999})); },
                 read, {"truncated", "bytes needed"});
  expect_refused(file, good, [](std::string& d) { replace_once(d, raw(0.4375) + raw(std::uint32_t{2}), raw(0.4375) + raw(std::uint32_t{0xfffffff0u})); },
                 read, {"truncated", "bytes needed"});
  // The header reader (material stores) checks the same header fields.
  std::string d = good;
  replace_once(d, raw(406.0), raw(399.0));
  write_resealed(file, d);
  CHECK_THROWS_AS(read_feather_material_header(file), InputFileError);
}

TEST_CASE("reader hardening: .ffs forged counts are refused at once, content validated", "[reader-hardening]") {
  const fs::path dir = scratch("ffs");
  FarFieldSet set;
  set.metadata = {{"species", "test"}};
  FarFieldUnit u;
  u.lambda_nm = 532.0;
  u.nominal = {0.1, -0.2};
  u.pattern_count = 2;
  for (int n = 0; n < 2; ++n) {
    FarField ff;
    ff.lambda_nm = 532.0;
    ff.incident = {0.1, -0.2};
    ff.phi_o_rad = {-0.5, 0.5, 0.7};
    ff.incident_power = {1.5, 1.5};
    for (int p = 0; p < 2; ++p)
      for (int j = 0; j < 3; ++j) ff.field[p].push_back({Complex(n, j), Complex(p, -j), Complex(0.25, 0.5)});
    u.instances.push_back(ff);
  }
  set.units.push_back(u);
  const fs::path good_file = dir / "good.ffs", file = dir / "bad.ffs";
  write_far_field_set(set, good_file);
  const std::string good = bytes_of(good_file);
  REQUIRE(read_far_field_set(good_file).units.size() == 1);
  const auto read = [](const fs::path& f) { (void)read_far_field_set(f); };
  // header_bytes sits after the magic and the version (byte 12).
  expect_refused(file, good, [](std::string& d) { d.replace(12, 4, raw(std::uint32_t{0xfffffff0u})); }, read,
                 {"truncated", "metadata"});
  expect_refused(file, good, [](std::string& d) { replace_once(d, raw(std::uint64_t{1}), raw(std::uint64_t{1} << 60)); }, read,
                 {"units", "remain"});
  expect_refused(file, good, [](std::string& d) { replace_once(d, raw(std::uint32_t{2}) + raw(std::uint32_t{2}) + raw(std::uint32_t{3}), raw(std::uint32_t{0x7fffffffu}) + raw(std::uint32_t{2}) + raw(std::uint32_t{3})); },
                 read, {"instances"});
  expect_refused(file, good, [](std::string& d) { replace_once(d, raw(std::uint32_t{2}) + raw(std::uint32_t{3}), raw(std::uint32_t{2}) + raw(std::uint32_t{0xffffffffu})); },
                 read, {"directions"});
  expect_refused(file, good, [](std::string& d) { replace_once(d, raw(532.0), raw(kNaN)); }, read, {"unit 0 lambda_nm"});
  expect_refused(file, good, [](std::string& d) { replace_once(d, raw(0.7), raw(1e30)); }, read, {"phi_o_rad[2]"});
  // The last field value written: instance 1, polarisation 1, direction 2.
  expect_refused(file, good, [](std::string& d) { d.replace(d.rfind(raw(0.25f) + raw(0.5f)), 4, raw(std::numeric_limits<float>::infinity())); },
                 read, {"instance 1 field[1][2]", "not finite"});
}

TEST_CASE("reader hardening: .plt forged sizes and bad axes are refused with the file named", "[reader-hardening]") {
  const fs::path dir = scratch("plt");
  ReflectionTable t(TableGrid::uniform(400, 700, 3, 4, 5), {"test-crystal", 190.0, "0123456789abcdef", 10.0, "unit test", ""});
  t.at(0, 0, 0).ss = {0.125, 0.0};
  const fs::path good_file = dir / "good.plt", file = dir / "bad.plt";
  t.save(good_file);
  const std::string good = bytes_of(good_file);
  REQUIRE(ReflectionTable::load(good_file).content_hash() == t.content_hash());
  const auto read = [](const fs::path& f) { (void)ReflectionTable::load(f); };
  // The three axis sizes follow magic, version and byte order (byte 16).
  expect_refused(file, good, [](std::string& d) { d.replace(16, 4, raw(std::uint32_t{0xffffffffu})); }, read,
                 {"truncated"});
  expect_refused(file, good, [](std::string& d) { d.replace(20, 4, raw(std::uint32_t{5})); }, read, {"size mismatch"});
  expect_refused(file, good, [](std::string& d) { replace_once(d, raw(550.0), raw(800.0)); }, read,
                 {"lambda_nm[2]", "strictly increasing"});
  expect_refused(file, good, [](std::string& d) { replace_once(d, raw(190.0), raw(kNaN)); }, read, {"period_nm"});
  expect_refused(file, good, [](std::string& d) { replace_once(d, raw(0.125), raw(kNaN)); }, read, {"Jones entry 0", "not finite"});
}

TEST_CASE("reader hardening: inputs that are not regular files are refused at once", "[reader-hardening]") {
  const fs::path dir = scratch("kinds");
  const fs::path folder = dir / "folder.plt", fifo = dir / "fifo.plm";
  fs::create_directories(folder);
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  for (const fs::path& p : {folder, fifo, fs::path("/dev/null")}) {
    const std::string kind = p == folder ? "directory" : p == fifo ? "FIFO" : "device";
    INFO(p);
    CHECK_THROWS_WITH(read_feather_material(p), Catch::Contains(p.string()) && Catch::Contains(kind));
    CHECK_THROWS_AS(read_feather_material_header(p), InputFileError);
    CHECK_THROWS_WITH(ReflectionTable::load(p), Catch::Contains(p.string()) && Catch::Contains(kind));
    CHECK_THROWS_WITH(read_far_field_set(p), Catch::Contains(p.string()) && Catch::Contains(kind));
    CHECK_THROWS_WITH(read_journal(p), Catch::Contains(p.string()) && Catch::Contains(kind));
  }
  CHECK_THROWS_AS(read_feather_material(dir / "missing.plm"), InputFileError);
}

TEST_CASE("reader hardening: a damaged journal record is skipped alone", "[reader-hardening]") {
  std::string data = "plumage-characterize-journal 2\nfingerprint\nconfig_hash 0\ninputs 0\n";
  std::vector<std::size_t> starts;
  for (std::uint32_t a = 1; a <= 4; ++a) {
    GroupRecord r;
    r.w = 0;
    r.a = a;
    r.units.resize(2);
    r.units[0].energy = 0.25 * a;
    starts.push_back(data.size());
    data += serialize(r);
  }
  const JournalContents whole = parse_journal(data, "j");
  REQUIRE(whole.records.size() == 4);
  CHECK(whole.damaged.empty());
  // One flipped byte inside record 2 (a = 2): records 1, 3, 4 kept, the damage reported.
  std::string flipped = data;
  flipped[starts[1] + 30] ^= 0x10;
  const JournalContents j = parse_journal(flipped, "j");
  REQUIRE(j.records.size() == 3);
  CHECK(j.records[0].a == 1);
  CHECK(j.records[1].a == 3);
  CHECK(j.records[2].a == 4);
  REQUIRE(j.damaged.size() == 1);
  CHECK(j.damaged[0].offset == starts[1]);
  CHECK(j.damaged[0].end == starts[2]);
  CHECK(j.valid_bytes == data.size());
  // A flipped magic or length is skipped the same way.
  std::string magic = data;
  magic[starts[2]] ^= 0x01;
  CHECK(parse_journal(magic, "j").records.size() == 3);
  // A torn tail (a kill while appending) is no damage: valid bytes end at the last good record.
  const std::string torn = data.substr(0, data.size() - 5);
  const JournalContents t = parse_journal(torn, "j");
  CHECK(t.records.size() == 3);
  CHECK(t.damaged.empty());
  CHECK(t.valid_bytes == starts[3]);
  // A whole last record with a flipped byte is damage (reported), and dropped like a torn tail.
  std::string last = data;
  last[starts[3] + 30] ^= 0x10;
  const JournalContents l = parse_journal(last, "j");
  CHECK(l.records.size() == 3);
  REQUIRE(l.damaged.size() == 1);
  CHECK(l.damaged[0].offset == starts[3]);
  CHECK(l.valid_bytes == starts[3]);
}
