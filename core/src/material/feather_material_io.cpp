// FeatherMaterial file (.plm): binary, little-endian, versioned, FNV-1a checksummed, written
// atomically. Layout: docs/formats.md, section "Feather material (.plm)". The header (every
// field before the node tables) is read on its own by read_feather_material_header, without
// the tables: a material store compares headers only.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string_view>

#include "plumage/atomic_file.hpp"
#include "plumage/checksum.hpp"
#include "plumage/error.hpp"
#include "plumage/feather_material.hpp"
#include "plumage/input_file.hpp"

namespace plumage {

namespace {

constexpr char kMagic[8] = {'P', 'L', 'U', 'M', 'P', 'L', 'M', '\0'};
constexpr std::size_t kMaxString = 1 << 16;
constexpr std::size_t kHeaderChunk = 1 << 16;

// Bounds of each stored node parameter (kMaterialFields order). Roughness and the shares are
// bounded by their meaning with room for the grazing extrapolation; the scales F·cosθ·cosφ are
// albedos (≤ 1 for a passive surface, far less than 1e3 even when extrapolated); azimuths are
// angles; the correlation ratio l/l0 is positive and below 1e6.
struct Range {
  double lo, hi;
};
constexpr Range kNodeRange[kMaterialParameters] = {{-10, 10},   {-7, 7},     {-1e3, 1e3}, {-10, 10},
                                                   {-7, 7},     {-1e3, 1e3}, {-1, 2},     {-1e6, 1e6}};

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

struct Writer {
  std::string bytes;
  template <class T>
  void put(T v) {
    bytes.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void put_string(const std::string& s) {
    put<std::uint32_t>(static_cast<std::uint32_t>(s.size()));
    bytes.append(s);
  }
};

// Reads from bytes in memory, or (header only) from a stream as far as needed.
class Reader {
 public:
  Reader(const std::string& data, std::size_t end, const std::filesystem::path& file)
      : data_(data), end_(end), file_(file) {}
  Reader(InputFile& in, const std::filesystem::path& file) : own_(), data_(own_), end_(0), file_(file), in_(&in) {}

  template <class T>
  T get() {
    need(sizeof(T));
    T v;
    std::memcpy(&v, data_.data() + pos_, sizeof v);
    pos_ += sizeof v;
    return v;
  }
  std::string get_string(const char* field) {
    const auto n = get<std::uint32_t>();
    if (n > kMaxString) fail(std::string(field) + ": string of " + std::to_string(n) + " bytes is implausible");
    need(n);
    std::string s = data_.substr(pos_, n);
    pos_ += n;
    return s;
  }
  void need(std::size_t n) {
    // A size read from the file is checked against the file's own size before it is read or
    // allocated: a forged count fails here, at once.
    const std::uintmax_t size = in_ ? in_->size() : end_;
    if (n > size || pos_ > size - n)
      fail("truncated feather material: " + std::to_string(n) + " bytes needed at byte " + std::to_string(pos_) +
           ", the file holds " + std::to_string(size));
    while (in_ && pos_ + n > end_) {
      const std::size_t want = std::max(kHeaderChunk, pos_ + n - end_);
      own_.resize(end_ + want);
      const std::size_t got = in_->read(own_.data() + end_, want);
      end_ += got;
      own_.resize(end_);
      if (got == 0) break;
    }
    if (pos_ + n > end_) fail("truncated feather material (at byte " + std::to_string(pos_) + ")");
  }
  [[noreturn]] void fail(const std::string& what) const { throw InputFileError(file_.string(), what); }
  std::size_t position() const { return pos_; }

 private:
  std::string own_;  // the stream's bytes read so far
  const std::string& data_;
  std::size_t end_;
  std::filesystem::path file_;
  InputFile* in_ = nullptr;
  std::size_t pos_ = 0;
};

void check_material(const FeatherMaterial& m) {
  const std::size_t per_bin = static_cast<std::size_t>(m.grid + 1) * static_cast<std::size_t>(m.grid + 1);
  if (m.grid < 1) throw Error("feather material: grid must be >= 1");
  if (m.lambda_nm.empty()) throw Error("feather material: no wavelength bins");
  if (m.nodes.size() != per_bin * m.lambda_nm.size())
    throw Error("feather material: " + std::to_string(m.nodes.size()) + " nodes, expected " +
                std::to_string(per_bin * m.lambda_nm.size()));
  if (m.noise.samples < 1 || m.noise.functions.size() % static_cast<std::size_t>(m.noise.samples) != 0)
    throw Error("feather material: noise pool size is not a multiple of its sample count");
}

void check_version(std::uint32_t version, const std::filesystem::path& file) {
  if (version < 1 || version > FeatherMaterial::kFormatVersion)
    throw InputFileError(file.string(), "feather material version " + std::to_string(version) + ", this build reads 1 to " +
                                            std::to_string(FeatherMaterial::kFormatVersion));
}

// The header's numbers: finite, in range, the wavelength grid strictly increasing.
void check_header_values(const FeatherMaterialHeader& h, const Reader& r) {
  const auto scalar = [&](const char* field, double v) {
    if (!std::isfinite(v) || v < 0) r.fail(std::string(field) + ": " + number(v) + ", expected a finite value >= 0");
  };
  scalar("sigma", h.sigma);
  scalar("l0", h.l0);
  scalar("bin_width_nm", h.bin_width_nm);
  for (std::size_t w = 0; w < h.lambda_nm.size(); ++w) {
    const double l = h.lambda_nm[w];
    if (!std::isfinite(l) || l <= 0 || l > kFileMaxWavelengthNm)
      r.fail("lambda_nm[" + std::to_string(w) + "]: " + number(l) + " nm, expected in (0, " + number(kFileMaxWavelengthNm) + "]");
    if (w > 0 && !(l > h.lambda_nm[w - 1]))
      r.fail("lambda_nm[" + std::to_string(w) + "]: " + number(l) + " nm after " + number(h.lambda_nm[w - 1]) +
             " nm: the wavelengths must be strictly increasing");
  }
}

// The tables' numbers: finite and in generous physical ranges (stored nodes include the grazing
// extrapolation, which lookup() clamps later, so the ranges bound damage, not fits).
void check_table_values(const FeatherMaterial& m, const Reader& r) {
  const std::size_t per_bin = static_cast<std::size_t>(m.grid + 1) * static_cast<std::size_t>(m.grid + 1);
  for (std::size_t k = 0; k < m.nodes.size(); ++k) {
    for (std::size_t f = 0; f < kMaterialParameters; ++f) {
      const double v = m.nodes[k].*kMaterialFields[f];
      if (!std::isfinite(v) || v < kNodeRange[f].lo || v > kNodeRange[f].hi)
        r.fail("node " + std::to_string(k) + " (wavelength bin " + std::to_string(k / per_bin) + ", node " +
               std::to_string(k % per_bin) + ") " + kMaterialFieldNames[f] + ": " + number(v) + ", expected in [" +
               number(kNodeRange[f].lo) + ", " + number(kNodeRange[f].hi) + "]");
    }
  }
  if (!std::isfinite(m.noise.lag1) || m.noise.lag1 < -1 || m.noise.lag1 > 1)
    r.fail("noise lag1: " + number(m.noise.lag1) + ", expected a correlation in [-1, 1]");
  for (std::size_t k = 0; k < m.noise.functions.size(); ++k)
    if (!std::isfinite(m.noise.functions[k]))
      r.fail("noise function " + std::to_string(k / static_cast<std::size_t>(m.noise.samples)) + ", sample " +
             std::to_string(k % static_cast<std::size_t>(m.noise.samples)) + ": not finite");
}

// Every field before the node tables, after magic and version.
void read_header(Reader& r, std::uint32_t version, FeatherMaterialHeader& h) {
  h.version = version;
  h.label = r.get_string("label");
  h.config_hash = r.get_string("config_hash");
  h.fidelity = r.get_string("fidelity");
  if (version >= 2) h.warnings = r.get_string("warnings");
  if (version >= 3) {
    h.key = r.get_string("key");
    h.key_text = r.get_string("key_text");
  }
  h.sigma = r.get<double>();
  h.l0 = r.get<double>();
  h.bin_width_nm = r.get<double>();
  h.grid = r.get<std::int32_t>();
  if (h.grid < 1 || h.grid > 1000) r.fail("grid: " + std::to_string(h.grid) + " outside [1, 1000]");
  const auto bins = r.get<std::uint32_t>();
  if (bins < 1 || bins > 100000) r.fail("wavelength bins: " + std::to_string(bins) + " outside [1, 100000]");
  r.need(bins * sizeof(double));
  h.lambda_nm.resize(bins);
  for (double& l : h.lambda_nm) l = r.get<double>();
  check_header_values(h, r);
}

}  // namespace

void write_feather_material(const std::filesystem::path& file, const FeatherMaterial& m) {
  check_material(m);
  Writer w;
  w.bytes.append(kMagic, sizeof kMagic);
  w.put<std::uint32_t>(FeatherMaterial::kFormatVersion);
  w.put_string(m.label);
  w.put_string(m.config_hash);
  w.put_string(m.fidelity);
  w.put_string(m.warnings);
  w.put_string(m.key);
  w.put_string(m.key_text);
  w.put<double>(m.sigma);
  w.put<double>(m.l0);
  w.put<double>(m.bin_width_nm);
  w.put<std::int32_t>(m.grid);
  w.put<std::uint32_t>(static_cast<std::uint32_t>(m.lambda_nm.size()));
  for (double l : m.lambda_nm) w.put<double>(l);
  w.put<std::uint32_t>(kMaterialParameters);
  for (const MaterialNode& n : m.nodes)
    for (auto field : kMaterialFields) w.put<double>(n.*field);
  w.put<std::int32_t>(m.noise.samples);
  w.put<double>(m.noise.lag1);
  w.put<std::uint32_t>(static_cast<std::uint32_t>(m.noise.count()));
  w.bytes.append(reinterpret_cast<const char*>(m.noise.functions.data()), m.noise.functions.size() * sizeof(float));
  w.put<std::uint64_t>(fnv1a(w.bytes));
  write_file_atomically(file, [&](std::ostream& out) { out.write(w.bytes.data(), static_cast<std::streamsize>(w.bytes.size())); },
                        /*binary=*/true);
}

FeatherMaterialHeader read_feather_material_header(const std::filesystem::path& file) {
  InputFile in(file, "feather material");
  Reader r(in, file);
  r.need(sizeof kMagic + 4);
  const auto magic = r.get<std::array<char, sizeof kMagic>>();
  if (std::memcmp(magic.data(), kMagic, sizeof kMagic) != 0) r.fail("not a plumage feather material (bad magic)");
  const auto version = r.get<std::uint32_t>();
  check_version(version, file);
  FeatherMaterialHeader h;
  read_header(r, version, h);
  return h;
}

FeatherMaterial read_feather_material(const std::filesystem::path& file) {
  const std::string data = read_input_file(file, "feather material");
  if (data.size() < sizeof kMagic + 4 + 8 || std::memcmp(data.data(), kMagic, sizeof kMagic) != 0)
    throw InputFileError(file.string(), "not a plumage feather material (bad magic)");
  std::uint32_t version;
  std::memcpy(&version, data.data() + sizeof kMagic, 4);
  check_version(version, file);
  std::uint64_t stored;
  std::memcpy(&stored, data.data() + data.size() - 8, 8);
  if (stored != fnv1a(std::string_view(data).substr(0, data.size() - 8)))
    throw InputFileError(file.string(), "checksum mismatch (corrupt or truncated feather material)");

  Reader r(data, data.size() - 8, file);
  (void)r.get<std::uint64_t>();  // magic
  (void)r.get<std::uint32_t>();  // version
  FeatherMaterialHeader h;
  read_header(r, version, h);
  FeatherMaterial m;
  m.label = std::move(h.label);
  m.config_hash = std::move(h.config_hash);
  m.fidelity = std::move(h.fidelity);
  m.warnings = std::move(h.warnings);
  m.key = std::move(h.key);
  m.key_text = std::move(h.key_text);
  m.sigma = h.sigma;
  m.l0 = h.l0;
  m.bin_width_nm = h.bin_width_nm;
  m.grid = h.grid;
  m.lambda_nm = std::move(h.lambda_nm);
  const auto params = r.get<std::uint32_t>();
  if (params != kMaterialParameters)
    r.fail("parameters per node: " + std::to_string(params) + ", expected " + std::to_string(kMaterialParameters));
  const std::size_t per_bin = static_cast<std::size_t>(m.grid + 1) * static_cast<std::size_t>(m.grid + 1);
  r.need(per_bin * m.lambda_nm.size() * kMaterialParameters * sizeof(double));
  m.nodes.resize(per_bin * m.lambda_nm.size());
  for (MaterialNode& n : m.nodes)
    for (auto field : kMaterialFields) n.*field = r.get<double>();
  m.noise.samples = r.get<std::int32_t>();
  if (m.noise.samples < 1 || m.noise.samples > (1 << 20))
    r.fail("noise samples: " + std::to_string(m.noise.samples) + " outside [1, 2^20]");
  m.noise.lag1 = r.get<double>();
  const auto count = r.get<std::uint32_t>();
  const std::size_t values = static_cast<std::size_t>(count) * static_cast<std::size_t>(m.noise.samples);
  r.need(values * sizeof(float));
  m.noise.functions.resize(values);
  // No functions: nothing to copy (memcpy from/to an empty vector's null data() is undefined;
  // found by fuzz/fuzz_plm, input in fuzz/regressions/plm).
  if (values > 0) std::memcpy(m.noise.functions.data(), data.data() + r.position(), values * sizeof(float));
  if (r.position() + values * sizeof(float) + 8 != data.size()) r.fail("trailing bytes in feather material");
  check_table_values(m, r);
  return m;
}

}  // namespace plumage
