#include "plumage/checksum.hpp"
#include "plumage/far_field_set.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>

#include "plumage/atomic_file.hpp"
#include "plumage/config_document.hpp"
#include "plumage/error.hpp"
#include "plumage/input_file.hpp"

namespace plumage {

namespace {

constexpr char kMagic[8] = {'P', 'L', 'U', 'M', 'F', 'F', 'S', '\0'};

class Writer {
 public:
  template <class T>
  void put(T v) {
    const char* p = reinterpret_cast<const char*>(&v);
    bytes.append(p, sizeof v);
  }
  std::string bytes;
};

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

// Reads the bytes before the checksum; every failure is an InputFileError naming the byte offset.
class Reader {
 public:
  Reader(const std::string& data, const std::filesystem::path& file) : data_(data), end_(data.size() - 8), file_(file) {}
  template <class T>
  T get() {
    need(sizeof(T), "a value");
    T v;
    std::memcpy(&v, data_.data() + pos_, sizeof v);
    pos_ += sizeof v;
    return v;
  }
  std::string get_bytes(std::size_t n) {
    need(n, "the metadata");
    std::string s = data_.substr(pos_, n);
    pos_ += n;
    return s;
  }
  // Refuses a size read from the file that the rest of the file cannot hold, before anything of
  // that size is allocated or read: `count` items of `bytes` each.
  void need(std::uint64_t count, std::uint64_t bytes, const std::string& what) {
    const std::uint64_t left = end_ - pos_;
    if (bytes != 0 && count > left / bytes)
      fail("truncated far-field set or forged count: " + what + " needs " + std::to_string(count) + " x " +
           std::to_string(bytes) + " bytes at byte " + std::to_string(pos_) + ", " + std::to_string(left) + " remain");
  }
  void need(std::uint64_t n, const std::string& what) { need(n, 1, what); }
  [[noreturn]] void fail(const std::string& what) const { throw InputFileError(file_.string(), what); }
  // A stored number: finite and within [lo, hi].
  double checked(double v, double lo, double hi, const std::string& field) const {
    if (!std::isfinite(v) || v < lo || v > hi)
      fail(field + ": " + number(v) + ", expected a finite value in [" + number(lo) + ", " + number(hi) + "] (byte " +
           std::to_string(pos_ - 8) + ")");
    return v;
  }
  std::size_t position() const { return pos_; }

 private:
  const std::string& data_;
  std::size_t end_;
  std::filesystem::path file_;
  std::size_t pos_ = 0;
};

// One unit, its sizes checked against the bytes left before they are allocated and its numbers
// finite and in range (angles within a turn, wavelengths as input_file.hpp bounds them).
FarFieldUnit read_unit(Reader& r, const std::string& unit) {
  constexpr double kTurn = 2 * 3.14159265358979323846;
  FarFieldUnit u;
  u.lambda_nm = r.checked(r.get<double>(), 1e-9, kFileMaxWavelengthNm, unit + " lambda_nm");
  u.nominal.theta_rad = r.checked(r.get<double>(), -kTurn, kTurn, unit + " theta_rad");
  u.nominal.phi_rad = r.checked(r.get<double>(), -kTurn, kTurn, unit + " phi_rad");
  const auto instances = r.get<std::uint32_t>();
  u.pattern_count = r.get<std::uint32_t>();
  const auto dirs = r.get<std::uint32_t>();
  if (u.pattern_count > dirs)
    r.fail(unit + " pattern_count: " + std::to_string(u.pattern_count) + " of only " + std::to_string(dirs) + " directions");
  r.need(dirs, 8, unit + " directions");
  std::vector<double> phi_o(dirs);
  for (std::uint32_t j = 0; j < dirs; ++j) phi_o[j] = r.checked(r.get<double>(), -kTurn, kTurn, unit + " phi_o_rad[" + std::to_string(j) + "]");
  const std::uint64_t instance_bytes = 3 * 8 + std::uint64_t{dirs} * 2 * 3 * 2 * 4;
  r.need(instances, instance_bytes, unit + " instances");
  for (std::uint32_t n = 0; n < instances; ++n) {
    const std::string in = unit + " instance " + std::to_string(n);
    FarField ff;
    ff.lambda_nm = u.lambda_nm;
    ff.incident = {u.nominal.theta_rad, r.checked(r.get<double>(), -kTurn, kTurn, in + " incident phi_rad")};
    const double p0 = r.checked(r.get<double>(), 0, 1e300, in + " incident_power[0]");
    ff.incident_power = {p0, r.checked(r.get<double>(), 0, 1e300, in + " incident_power[1]")};
    ff.phi_o_rad = phi_o;
    for (int p = 0; p < 2; ++p) {
      ff.field[p].resize(dirs);
      for (std::size_t j = 0; j < dirs; ++j) {
        for (int c = 0; c < 3; ++c) {
          const float re = r.get<float>(), im = r.get<float>();
          if (!std::isfinite(re) || !std::isfinite(im))
            r.fail(in + " field[" + std::to_string(p) + "][" + std::to_string(j) + "]: not finite (byte " +
                   std::to_string(r.position() - 8) + ")");
          ff.field[p][j][c] = {re, im};
        }
      }
    }
    u.instances.push_back(std::move(ff));
  }
  return u;
}

}  // namespace

void write_far_field_set(const FarFieldSet& set, const std::filesystem::path& file) {
  Writer w;
  w.bytes.append(kMagic, sizeof kMagic);
  w.put<std::uint32_t>(kFarFieldSetVersion);
  std::string header;
  for (const auto& [k, v] : set.metadata) {
    if (k.find_first_of("=\n") != std::string::npos || v.find('\n') != std::string::npos) {
      throw Error("far-field set metadata must be single-line key=value: " + k);
    }
    header += k + "=" + v + "\n";
  }
  w.put<std::uint32_t>(static_cast<std::uint32_t>(header.size()));
  w.bytes += header;
  w.put<std::uint64_t>(set.units.size());
  for (const auto& u : set.units) {
    const std::size_t dirs = u.instances.empty() ? 0 : u.instances.front().phi_o_rad.size();
    w.put<double>(u.lambda_nm);
    w.put<double>(u.nominal.theta_rad);
    w.put<double>(u.nominal.phi_rad);
    w.put<std::uint32_t>(static_cast<std::uint32_t>(u.instances.size()));
    w.put<std::uint32_t>(static_cast<std::uint32_t>(u.pattern_count));
    w.put<std::uint32_t>(static_cast<std::uint32_t>(dirs));
    if (!u.instances.empty()) {
      for (double phi : u.instances.front().phi_o_rad) w.put<double>(phi);
    }
    for (const auto& ff : u.instances) {
      if (ff.phi_o_rad.size() != dirs) throw Error("far-field set: instances differ in directions");
      w.put<double>(ff.incident.phi_rad);
      w.put<double>(ff.incident_power[0]);
      w.put<double>(ff.incident_power[1]);
      for (int p = 0; p < 2; ++p) {
        for (std::size_t j = 0; j < dirs; ++j) {
          for (int c = 0; c < 3; ++c) {
            w.put<float>(static_cast<float>(ff.field[p][j][c].real()));
            w.put<float>(static_cast<float>(ff.field[p][j][c].imag()));
          }
        }
      }
    }
  }
  w.put<std::uint64_t>(fnv1a(w.bytes));
  write_file_atomically(file, [&](std::ostream& out) { out.write(w.bytes.data(), static_cast<std::streamsize>(w.bytes.size())); }, true);
}

FarFieldSet read_far_field_set(const std::filesystem::path& file) {
  const std::string data = read_input_file(file, "far-field set");
  if (data.size() < sizeof kMagic + 8 || std::memcmp(data.data(), kMagic, sizeof kMagic) != 0) {
    throw InputFileError(file.string(), "not a plumage far-field set (bad magic)");
  }
  std::uint64_t stored = 0;
  std::memcpy(&stored, data.data() + data.size() - 8, 8);
  if (stored != fnv1a(std::string_view(data).substr(0, data.size() - 8))) {
    throw InputFileError(file.string(), "checksum mismatch (corrupt or truncated far-field set)");
  }
  Reader r(data, file);
  r.get_bytes(sizeof kMagic);
  const auto version = r.get<std::uint32_t>();
  if (version != kFarFieldSetVersion) {
    r.fail("far-field set version " + std::to_string(version) + " is not supported (this plumage reads version " +
           std::to_string(kFarFieldSetVersion) + ")");
  }
  FarFieldSet set;
  const auto header_bytes = r.get<std::uint32_t>();
  std::istringstream header(r.get_bytes(header_bytes));
  for (std::string line; std::getline(header, line);) {
    const auto eq = line.find('=');
    if (eq == std::string::npos || eq == 0) r.fail("header_bytes: metadata line \"" + line.substr(0, 60) + "\" is not key=value");
    set.metadata[line.substr(0, eq)] = line.substr(eq + 1);
  }
  const auto units = r.get<std::uint64_t>();
  constexpr std::uint64_t kUnitBytes = 3 * 8 + 3 * 4;  // a unit without directions or instances
  r.need(units, kUnitBytes, "units");
  for (std::uint64_t i = 0; i < units; ++i) set.units.push_back(read_unit(r, "unit " + std::to_string(i)));
  if (r.position() + 8 != data.size()) r.fail("trailing bytes in far-field set (after byte " + std::to_string(r.position()) + ")");
  return set;
}

std::vector<double> mean_reflectance_density(const FarFieldUnit& unit, int pol) {
  if (unit.instances.empty()) return {};
  std::vector<double> mean(unit.instances.front().phi_o_rad.size(), 0.0);
  for (const auto& ff : unit.instances) {
    for (std::size_t j = 0; j < mean.size(); ++j) {
      mean[j] += pol < 0 ? 0.5 * (ff.reflectance_density(0, j) + ff.reflectance_density(1, j))
                         : ff.reflectance_density(pol, j);
    }
  }
  for (auto& m : mean) m /= static_cast<double>(unit.instances.size());
  return mean;
}

}  // namespace plumage
