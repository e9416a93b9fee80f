// Records, journals and assembly for `plumage characterize` / `plumage merge`.
#include "characterize_records.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>

#include "plumage/checksum.hpp"
#include "plumage/diagnostics.hpp"
#include "plumage/error.hpp"
#include "plumage/fitter.hpp"
#include "plumage/random.hpp"

namespace plumage::cli {

namespace {

constexpr char kJournalMagic[] = "plumage-characterize-journal 1";
constexpr std::uint32_t kRecordMagic = 0x524d4c50;  // "PLMR"
// Bumped whenever the simulation or fitting code changes what a record holds, so that a journal
// or shard from older code is never mixed with new records.
// 3: records carry their warning codes; fits normalise the pattern's scale and give a zero lobe
// for near-zero energy (issue 9).
constexpr int kFitRevision = 3;

template <class T>
void put(std::string& s, T v) {
  s.append(reinterpret_cast<const char*>(&v), sizeof v);
}

template <class T>
bool get(const std::string& s, std::size_t& pos, std::size_t end, T& v) {
  if (pos + sizeof(T) > end) return false;
  std::memcpy(&v, s.data() + pos, sizeof v);
  pos += sizeof v;
  return true;
}

std::string hexfloat(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%a", v);
  return b;
}

}  // namespace

std::string CharacterizeSettings::fingerprint() const {
  std::ostringstream o;
  o << "fit_revision=" << kFitRevision << " label=" << label << " config_hash=" << config_hash << " variant=" << variant << " fidelity=" << fidelity
    << " instances=" << instances << " grid=" << grid << " lambda_nm=";
  for (std::size_t k = 0; k < lambda_nm.size(); ++k) o << (k ? "," : "") << hexfloat(lambda_nm[k]);
  o << " bin_width_nm=" << hexfloat(bin_width_nm) << " pattern=" << pattern_samples << " projected=" << projected_samples
    << " jitter_deg=" << hexfloat(jitter_deg) << " sigma=" << hexfloat(sigma) << " noise_functions=" << noise_functions;
  return o.str();
}

CharacterizeSettings CharacterizeSettings::from_fingerprint(const std::string& line) {
  std::map<std::string, std::string> kv;
  std::istringstream in(line);
  std::string token;
  while (in >> token) {
    const auto eq = token.find('=');
    if (eq == std::string::npos) throw Error("characterisation header: bad field '" + token + "'");
    kv[token.substr(0, eq)] = token.substr(eq + 1);
  }
  auto field = [&](const char* k) -> const std::string& {
    auto it = kv.find(k);
    if (it == kv.end()) throw Error(std::string("characterisation header: missing field ") + k);
    return it->second;
  };
  auto num = [&](const char* k) { return std::strtod(field(k).c_str(), nullptr); };
  CharacterizeSettings s;
  if (field("fit_revision") != std::to_string(kFitRevision))
    throw Error("characterisation records of fit revision " + field("fit_revision") + ", this build writes " +
                std::to_string(kFitRevision) + ": recompute them");
  s.label = field("label");
  s.config_hash = field("config_hash");
  s.variant = field("variant");
  s.fidelity = field("fidelity");
  s.instances = std::stoi(field("instances"));
  s.grid = std::stoi(field("grid"));
  std::istringstream l(field("lambda_nm"));
  for (std::string v; std::getline(l, v, ',');) s.lambda_nm.push_back(std::strtod(v.c_str(), nullptr));
  s.bin_width_nm = num("bin_width_nm");
  s.pattern_samples = std::stoi(field("pattern"));
  s.projected_samples = std::stoi(field("projected"));
  s.jitter_deg = num("jitter_deg");
  s.sigma = num("sigma");
  s.noise_functions = std::stoi(field("noise_functions"));
  if (s.fingerprint() != line) throw Error("characterisation header does not round-trip: " + line);
  return s;
}

std::string serialize(const GroupRecord& r) {
  std::string body;
  put<std::uint32_t>(body, r.w);
  put<std::uint32_t>(body, r.a);
  put<std::uint32_t>(body, static_cast<std::uint32_t>(r.units.size()));
  for (const UnitRecord& u : r.units) {
    for (auto f : kMaterialFields) put<double>(body, u.node.*f);
    put<double>(body, u.rel_l2_eff);
    put<double>(body, u.rel_l2_sta);
    put<double>(body, u.energy);
  }
  put<std::uint32_t>(body, static_cast<std::uint32_t>(r.autocorrelation.size()));
  for (double v : r.autocorrelation) put<double>(body, v);
  put<std::uint32_t>(body, static_cast<std::uint32_t>(r.warnings.size()));
  for (const std::string& code : r.warnings) {
    put<std::uint32_t>(body, static_cast<std::uint32_t>(code.size()));
    body += code;
  }
  std::string out;
  put<std::uint32_t>(out, kRecordMagic);
  put<std::uint64_t>(out, body.size());
  out += body;
  put<std::uint64_t>(out, fnv1a(body));
  return out;
}

std::string journal_header(const CharacterizeSettings& s) {
  return std::string(kJournalMagic) + "\n" + s.fingerprint() + "\n";
}

JournalContents read_journal(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error(file.string() + ": cannot open characterisation journal");
  const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  JournalContents j;
  const auto l1 = data.find('\n');
  const auto l2 = l1 == std::string::npos ? std::string::npos : data.find('\n', l1 + 1);
  if (l2 == std::string::npos || data.compare(0, l1, kJournalMagic) != 0)
    throw Error(file.string() + ": not a plumage characterisation journal or shard file (bad header)");
  j.fingerprint = data.substr(l1 + 1, l2 - l1 - 1);
  std::size_t pos = l2 + 1;
  j.valid_bytes = pos;
  while (pos < data.size()) {
    std::size_t p = pos;
    std::uint32_t magic;
    std::uint64_t len;
    if (!get(data, p, data.size(), magic) || magic != kRecordMagic || !get(data, p, data.size(), len)) break;
    if (len > data.size() || p + len + 8 > data.size()) break;
    const std::size_t body = p, end = p + len;
    std::uint64_t sum;
    std::memcpy(&sum, data.data() + end, 8);
    if (sum != fnv1a(std::string_view(data).substr(body, len))) break;
    GroupRecord r;
    std::uint32_t n = 0, nacf = 0;
    bool ok = get(data, p, end, r.w) && get(data, p, end, r.a) && get(data, p, end, n);
    for (std::uint32_t k = 0; ok && k < n; ++k) {
      UnitRecord u;
      for (auto f : kMaterialFields) ok = ok && get(data, p, end, u.node.*f);
      ok = ok && get(data, p, end, u.rel_l2_eff) && get(data, p, end, u.rel_l2_sta) && get(data, p, end, u.energy);
      r.units.push_back(u);
    }
    ok = ok && get(data, p, end, nacf);
    for (std::uint32_t k = 0; ok && k < nacf; ++k) {
      double v = 0;
      ok = get(data, p, end, v);
      r.autocorrelation.push_back(v);
    }
    std::uint32_t ncodes = 0;
    ok = ok && get(data, p, end, ncodes) && ncodes < 10000;
    for (std::uint32_t k = 0; ok && k < ncodes; ++k) {
      std::uint32_t len = 0;
      ok = get(data, p, end, len) && len <= end - p;
      if (ok) {
        r.warnings.emplace_back(data, p, len);
        p += len;
      }
    }
    if (!ok || p != end) break;
    j.records.push_back(std::move(r));
    pos = end + 8;
    j.valid_bytes = pos;
  }
  return j;
}

JournalWriter::JournalWriter(const std::filesystem::path& file, const CharacterizeSettings& s, std::uintmax_t valid_bytes)
    : file_(file) {
  const bool fresh = valid_bytes == 0;
  if (!fresh) std::filesystem::resize_file(file, valid_bytes);  // drop a torn tail
  fd_ = ::open(file.c_str(), O_WRONLY | O_CREAT | O_APPEND | (fresh ? O_TRUNC : 0), 0644);
  if (fd_ < 0) throw Error(file.string() + ": cannot open journal for writing: " + std::strerror(errno));
  if (fresh) {
    const std::string h = journal_header(s);
    if (::write(fd_, h.data(), h.size()) != static_cast<ssize_t>(h.size()))
      throw Error(file.string() + ": cannot write journal header");
    ::fsync(fd_);
  }
}

JournalWriter::~JournalWriter() {
  if (fd_ >= 0) ::close(fd_);
}

void JournalWriter::append(const GroupRecord& r) {
  const std::string bytes = serialize(r);
  if (::write(fd_, bytes.data(), bytes.size()) != static_cast<ssize_t>(bytes.size()))
    throw Error(file_.string() + ": cannot append to journal: " + std::strerror(errno));
  ::fdatasync(fd_);
}

namespace {

// One record per group, in group order; refuses gaps and conflicting duplicates.
std::vector<const GroupRecord*> ordered(const CharacterizeSettings& s, const std::vector<GroupRecord>& records) {
  std::vector<const GroupRecord*> by_group(s.group_count(), nullptr);
  for (const GroupRecord& r : records) {
    if (r.w >= s.lambda_nm.size() || r.a < 1 || r.a > static_cast<std::uint32_t>(s.grid) ||
        r.units.size() != static_cast<std::size_t>(s.grid))
      throw Error("characterisation record (w " + std::to_string(r.w) + ", a " + std::to_string(r.a) + ") does not fit the grid");
    const std::size_t g = r.w * static_cast<std::size_t>(s.grid) + (r.a - 1);
    if (by_group[g] && serialize(*by_group[g]) != serialize(r))
      throw Error("two different records for group (w " + std::to_string(r.w) + ", a " + std::to_string(r.a) + ")");
    by_group[g] = &r;
  }
  std::size_t missing = 0;
  for (auto* p : by_group) missing += p == nullptr;
  if (missing) throw Error(std::to_string(missing) + " of " + std::to_string(by_group.size()) + " work groups are missing");
  return by_group;
}

}  // namespace

// The material's warnings from its records, so the same for one process, shards, MPI ranks and
// resumed runs: per code (sorted), in how many work groups it was raised and the first group (in
// group order). The messages with their numbers went to the computing processes' stderr.
std::string material_warnings(const CharacterizeSettings& s, const std::vector<const GroupRecord*>& groups) {
  std::map<std::string, std::pair<std::size_t, const GroupRecord*>> by_code;
  for (const GroupRecord* r : groups) {
    for (const std::string& code : r->warnings) {
      auto& [count, first] = by_code[code];
      ++count;
      if (!first || std::make_pair(r->w, r->a) < std::make_pair(first->w, first->a)) first = r;
    }
  }
  std::ostringstream out;
  for (const auto& [code, entry] : by_code) {
    out << code << ": raised while computing " << entry.first << " of " << groups.size()
        << " work groups, first at lambda = " << s.lambda_nm[entry.second->w] << " nm, cos theta_i = "
        << entry.second->a << "/" << s.grid << "\n";
  }
  return out.str();
}

FeatherMaterial assemble_material(const CharacterizeSettings& s, const std::vector<GroupRecord>& records) {
  const auto groups = ordered(s, records);
  FeatherMaterial m;
  m.label = s.label;
  m.config_hash = s.config_hash;
  m.fidelity = s.fidelity;
  m.warnings = material_warnings(s, groups);
  m.sigma = s.sigma;
  m.grid = s.grid;
  m.lambda_nm = s.lambda_nm;
  m.bin_width_nm = s.bin_width_nm;
  m.nodes.resize(s.lambda_nm.size() * static_cast<std::size_t>((s.grid + 1) * (s.grid + 1)));
  const std::vector<double>* acf = nullptr;
  for (const GroupRecord* r : groups) {
    for (int b = 1; b <= s.grid; ++b) m.node(r->w, static_cast<int>(r->a), b) = r->units[b - 1].node;
    if (!r->autocorrelation.empty()) acf = &r->autocorrelation;
  }
  assemble_tables(m);
  if (!acf) throw Error("the reference work group (first wavelength, normal incidence) carries no autocorrelation");
  const std::uint64_t seed = splitmix64(name_hash(s.config_hash) ^ splitmix64(name_hash(s.variant)));
  m.noise = synthesize_noise_pool(*acf, s.noise_functions, seed);
  return m;
}

std::string fit_quality_summary(const CharacterizeSettings& s, const std::vector<GroupRecord>& records) {
  std::vector<double> eff, sta, eff_w;
  double wsum = 0, werr = 0;
  for (const GroupRecord& r : records) {
    for (const UnitRecord& u : r.units) {
      eff.push_back(u.rel_l2_eff);
      sta.push_back(u.rel_l2_sta);
      werr += u.energy * u.rel_l2_eff;
      wsum += u.energy;
    }
  }
  if (eff.empty()) return "no units";
  auto q = [](std::vector<double> v, double p) {
    std::sort(v.begin(), v.end());
    return v[static_cast<std::size_t>(p * static_cast<double>(v.size() - 1))];
  };
  std::ostringstream o;
  o.precision(3);
  o << s.label << " (" << s.fidelity << ", " << eff.size() << " units): relative L2 of the mean-lobe fit on the cone: median "
    << q(eff, 0.5) << ", 90th percentile " << q(eff, 0.9) << ", max " << q(eff, 1.0) << ", energy-weighted mean "
    << (wsum > 0 ? werr / wsum : 0.0) << "; statistics lobe: median " << q(sta, 0.5) << ", 90th percentile " << q(sta, 0.9);
  return o.str();
}

}  // namespace plumage::cli
