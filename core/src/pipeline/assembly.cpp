// The material from a complete set of work records (spec §4.7 tables, §4.8 noise pool), in one
// process, so single, sharded, MPI and resumed runs write identical bytes.
#include <string>

#include "plumage/characterize_records.hpp"
#include "plumage/error.hpp"
#include "plumage/fitter.hpp"
#include "plumage/material_key.hpp"
#include "plumage/random.hpp"
#include "warning_attribution.hpp"

namespace plumage {

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

// The noise pool's seed: the same for every way of running, different per config and variant.
// It derives from the variant's comment-independent identity (config_digest, material_key.hpp:
// the merged variant's canonical text and the files it names), not from the species file's
// bytes, so a comment edit, which keeps the material's key, keeps its noise pool too.
std::uint64_t noise_pool_seed(const CharacterizeSettings& s) {
  return splitmix64(name_hash(config_digest(s.inputs)) ^ splitmix64(name_hash(s.variant)));
}

}  // namespace

FeatherMaterial assemble_material(const CharacterizeSettings& s, const std::vector<GroupRecord>& records) {
  const auto groups = ordered(s, records);
  FeatherMaterial m;
  m.label = s.label;
  m.config_hash = s.config_hash;
  m.fidelity = s.fidelity;
  m.warnings = material_warnings(s, groups);
  m.key = s.key();
  m.key_text = s.key_text();
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
  m.noise = synthesize_noise_pool(*acf, s.noise_functions, noise_pool_seed(s));
  return m;
}

}  // namespace plumage
