// FNV-1a (64 bit): the checksum of every binary file plumage writes (.ffs, .plt, .plm,
// characterisation journals) and the content hash of configs (fnv1a_hex in config_document.hpp).
// Not cryptographic: it detects corruption and identifies content, nothing more.
#pragma once

#include <cstdint>
#include <string_view>

namespace plumage {

inline constexpr std::uint64_t kFnv1aOffset = 14695981039346656037ull;

// Chainable: fnv1a(b, fnv1a(a)) == fnv1a(a + b).
inline std::uint64_t fnv1a(std::string_view bytes, std::uint64_t h = kFnv1aOffset) {
  for (const unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

}  // namespace plumage
