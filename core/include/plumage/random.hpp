// Deterministic, counter-based random numbers for procedural geometry.
//
// Every random draw in plumage comes from a RandomStream keyed by a 64-bit seed. A stream's k-th
// value is a pure function of (key, k): SplitMix64 finalisers applied to the key and the counter,
// so results do not depend on thread count, machine or standard library (no <random>
// distributions, whose output is implementation-defined). Seeds derive from names with FNV-1a:
//   seed(instance) = mix(hash(species), hash(variant), instance index)
// and each independent ingredient of an instance (top roughness, melanosome sizes, ...) draws
// from its own sub-stream `RandomStream(seed, "purpose")`, so adding draws to one ingredient
// never shifts another.
#pragma once

#include <cstdint>
#include <string_view>

namespace plumage {

// SplitMix64 finaliser: a bijective 64-bit mixer.
constexpr std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// FNV-1a of a name (stable across machines).
constexpr std::uint64_t name_hash(std::string_view s) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (char c : s) {
    h ^= static_cast<unsigned char>(c);
    h *= 0x100000001b3ULL;
  }
  return h;
}

// The seed of instance `index` of (species, variant).
constexpr std::uint64_t instance_seed(std::string_view species, std::string_view variant,
                                      std::uint64_t index) {
  std::uint64_t s = splitmix64(name_hash(species));
  s = splitmix64(s ^ name_hash(variant));
  return splitmix64(s ^ splitmix64(index + 0x632be59bd9b4e019ULL));
}

class RandomStream {
 public:
  constexpr explicit RandomStream(std::uint64_t key) : key_(splitmix64(key)) {}
  constexpr RandomStream(std::uint64_t seed, std::string_view purpose)
      : key_(splitmix64(seed ^ splitmix64(name_hash(purpose)))) {}

  // The k-th raw value of the stream, without advancing it.
  constexpr std::uint64_t at(std::uint64_t k) const {
    return splitmix64(key_ ^ splitmix64(k * 0xd1342543de82ef95ULL + 1));
  }
  constexpr std::uint64_t next_u64() { return at(counter_++); }
  // Uniform in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(next_u64() >> 11) * 0x1.0p-53; }
  // Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  // Standard normal (Box-Muller from two uniforms; std::log/std::cos of the C library).
  double normal();
  std::uint64_t counter() const { return counter_; }

 private:
  std::uint64_t key_;
  std::uint64_t counter_ = 0;
};

}  // namespace plumage
