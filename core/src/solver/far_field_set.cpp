#include "plumage/checksum.hpp"
#include "plumage/far_field_set.hpp"

#include <cstring>
#include <fstream>
#include <sstream>

#include "plumage/atomic_file.hpp"
#include "plumage/config_document.hpp"
#include "plumage/error.hpp"

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

class Reader {
 public:
  Reader(const std::string& data, const std::filesystem::path& file) : data_(data), file_(file) {}
  template <class T>
  T get() {
    if (pos_ + sizeof(T) > data_.size()) throw Error(file_.string() + ": truncated far-field set");
    T v;
    std::memcpy(&v, data_.data() + pos_, sizeof v);
    pos_ += sizeof v;
    return v;
  }
  std::string get_bytes(std::size_t n) {
    if (pos_ + n > data_.size()) throw Error(file_.string() + ": truncated far-field set");
    std::string s = data_.substr(pos_, n);
    pos_ += n;
    return s;
  }
  std::size_t position() const { return pos_; }

 private:
  const std::string& data_;
  std::filesystem::path file_;
  std::size_t pos_ = 0;
};

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
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error(file.string() + ": cannot open far-field set");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  const std::string data = buffer.str();
  if (data.size() < sizeof kMagic + 8 || std::memcmp(data.data(), kMagic, sizeof kMagic) != 0) {
    throw Error(file.string() + ": not a plumage far-field set (bad magic)");
  }
  std::uint64_t stored = 0;
  std::memcpy(&stored, data.data() + data.size() - 8, 8);
  if (stored != fnv1a(std::string_view(data).substr(0, data.size() - 8))) {
    throw Error(file.string() + ": checksum mismatch (corrupt or truncated far-field set)");
  }
  Reader r(data, file);
  r.get_bytes(sizeof kMagic);
  const auto version = r.get<std::uint32_t>();
  if (version != kFarFieldSetVersion) {
    throw Error(file.string() + ": far-field set version " + std::to_string(version) +
                " is not supported (this plumage reads version " +
                std::to_string(kFarFieldSetVersion) + ")");
  }
  FarFieldSet set;
  std::istringstream header(r.get_bytes(r.get<std::uint32_t>()));
  for (std::string line; std::getline(header, line);) {
    const auto eq = line.find('=');
    if (eq != std::string::npos) set.metadata[line.substr(0, eq)] = line.substr(eq + 1);
  }
  const auto units = r.get<std::uint64_t>();
  for (std::uint64_t i = 0; i < units; ++i) {
    FarFieldUnit u;
    u.lambda_nm = r.get<double>();
    u.nominal.theta_rad = r.get<double>();
    u.nominal.phi_rad = r.get<double>();
    const auto instances = r.get<std::uint32_t>();
    u.pattern_count = r.get<std::uint32_t>();
    const auto dirs = r.get<std::uint32_t>();
    std::vector<double> phi_o(dirs);
    for (auto& phi : phi_o) phi = r.get<double>();
    for (std::uint32_t n = 0; n < instances; ++n) {
      FarField ff;
      ff.lambda_nm = u.lambda_nm;
      ff.incident = {u.nominal.theta_rad, r.get<double>()};
      ff.incident_power = {r.get<double>(), r.get<double>()};
      ff.phi_o_rad = phi_o;
      for (int p = 0; p < 2; ++p) {
        ff.field[p].resize(dirs);
        for (std::size_t j = 0; j < dirs; ++j) {
          for (int c = 0; c < 3; ++c) {
            const float re = r.get<float>(), im = r.get<float>();
            ff.field[p][j][c] = {re, im};
          }
        }
      }
      u.instances.push_back(std::move(ff));
    }
    set.units.push_back(std::move(u));
  }
  if (r.position() + 8 != data.size()) throw Error(file.string() + ": trailing bytes in far-field set");
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
