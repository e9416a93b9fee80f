// One work record as bytes and back (characterize_records.hpp; layout: docs/formats.md).
#include "records.hpp"

#include <cstring>

#include "plumage/checksum.hpp"

namespace plumage {

namespace {

template <class T>
void put(std::string& s, T v) {
  s.append(reinterpret_cast<const char*>(&v), sizeof v);
}

template <class T>
bool get(std::string_view s, std::size_t& pos, std::size_t end, T& v) {
  if (pos + sizeof(T) > end) return false;
  std::memcpy(&v, s.data() + pos, sizeof v);
  pos += sizeof v;
  return true;
}

// The body of one record between `p` and `end`; false if it does not parse exactly.
bool parse_body(std::string_view data, std::size_t p, std::size_t end, GroupRecord& r) {
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
      r.warnings.emplace_back(data.substr(p, len));
      p += len;
    }
  }
  // Optional (issue 23; absent in older records): the per-unit sites of per-direction codes.
  std::uint32_t nsites = 0;
  if (ok && p < end) ok = get(data, p, end, nsites) && nsites <= 1000000;
  for (std::uint32_t k = 0; ok && k < nsites; ++k) {
    GroupRecord::UnitWarning u;
    std::uint32_t len = 0;
    ok = get(data, p, end, len) && len <= end - p;
    if (!ok) break;
    u.code.assign(data.substr(p, len));
    p += len;
    ok = get(data, p, end, u.b) && get(data, p, end, u.instances) && get(data, p, end, u.worst);
    if (ok) r.unit_warnings.push_back(std::move(u));
  }
  return ok && p == end;
}

}  // namespace

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
  // Written only when there are any, so a record without them has the pre-issue-23 bytes.
  if (!r.unit_warnings.empty()) {
    put<std::uint32_t>(body, static_cast<std::uint32_t>(r.unit_warnings.size()));
    for (const GroupRecord::UnitWarning& u : r.unit_warnings) {
      put<std::uint32_t>(body, static_cast<std::uint32_t>(u.code.size()));
      body += u.code;
      put<std::uint32_t>(body, u.b);
      put<std::uint32_t>(body, u.instances);
      put<double>(body, u.worst);
    }
  }
  std::string out;
  put<std::uint32_t>(out, kRecordMagic);
  put<std::uint64_t>(out, body.size());
  out += body;
  put<std::uint64_t>(out, fnv1a(body));
  return out;
}

std::optional<GroupRecord> parse_record(std::string_view data, std::size_t& pos) {
  std::size_t p = pos;
  std::uint32_t magic;
  std::uint64_t len;
  if (!get(data, p, data.size(), magic) || magic != kRecordMagic || !get(data, p, data.size(), len)) return std::nullopt;
  if (len > data.size() || p + len + 8 > data.size()) return std::nullopt;
  const std::size_t body = p, end = p + len;
  std::uint64_t sum;
  std::memcpy(&sum, data.data() + end, 8);
  if (sum != fnv1a(data.substr(body, len))) return std::nullopt;
  GroupRecord r;
  if (!parse_body(data, body, end, r)) return std::nullopt;
  pos = end + 8;
  return r;
}

std::vector<GroupRecord> parse_records(std::string_view data, const std::string& name) {
  std::vector<GroupRecord> out;
  std::size_t pos = 0;
  while (pos < data.size()) {
    auto r = parse_record(data, pos);
    if (!r) throw Error(name + ": damaged work record at byte " + std::to_string(pos));
    out.push_back(std::move(*r));
  }
  return out;
}

}  // namespace plumage
