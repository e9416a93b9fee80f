// An exact memo of FeatherBsdf::incident_bin per tile: the same (BSDF, wavelength bin, ω_i) —
// bit for bit — returns the stored Incident. Exact hits are common: all triangles of a barbule
// share one shading frame, so a distant light's local direction is identical for every sample of
// a pixel that lands on that barbule. A hit returns what a miss computes, so images do not depend
// on the cache (or on which thread owns it). FeatherBsdf::incident costs ≈ 2 µs (measured,
// NOTES.md), the largest single cost of a feather vertex.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <memory>

#include "plumage/feather_bsdf.hpp"

namespace plumage::pathtracer {

class IncidentCache {
 public:
  IncidentCache() : entries_(std::make_unique<std::array<Entry, kSize>>()) {}

  const FeatherBsdf::Incident& get(const FeatherBsdf& bsdf, double lambda_nm, const Direction& wi) {
    std::uint64_t bits[3];
    key_bits(wi, bits);
    const std::size_t bin = bsdf.material().wavelength_bin(lambda_nm);
    Entry& e = slot(bsdf, bin, bits);
    if (matches(e, bsdf, bin, bits)) {
      ++hits_;
      return e.in;
    }
    ++misses_;
    store(e, bsdf, bin, bits, bsdf.incident_bin(bin, wi));
    return e.in;
  }

  // The Incidents of one direction at N wavelengths (copied out: two of them may share a slot).
  // Misses share FeatherBsdf::incident_geometry (|θ_i|, the table cells and weights), computed
  // once on the first miss; incident_bin(bin, geometry) gives the same bits as incident_bin(bin, wi).
  template <std::size_t N>
  void get(const FeatherBsdf& bsdf, const std::array<double, N>& lambda_nm, const Direction& wi,
           std::array<FeatherBsdf::Incident, N>& out) {
    std::uint64_t bits[3];
    key_bits(wi, bits);
    bool have_geometry = false;
    FeatherBsdf::IncidentGeometry geometry;
    for (std::size_t j = 0; j < N; ++j) {
      const std::size_t bin = bsdf.material().wavelength_bin(lambda_nm[j]);
      Entry& e = slot(bsdf, bin, bits);
      if (matches(e, bsdf, bin, bits)) {
        ++hits_;
        out[j] = e.in;
        continue;
      }
      ++misses_;
      if (!have_geometry) {
        geometry = bsdf.incident_geometry(wi);
        have_geometry = true;
      }
      store(e, bsdf, bin, bits, bsdf.incident_bin(bin, geometry));
      out[j] = e.in;
    }
  }
  std::uint64_t hits() const { return hits_; }
  std::uint64_t misses() const { return misses_; }

 private:
  struct Entry;
  static void key_bits(const Direction& wi, std::uint64_t* bits) {
    std::memcpy(&bits[0], &wi.x, 8);
    std::memcpy(&bits[1], &wi.y, 8);
    std::memcpy(&bits[2], &wi.z, 8);
  }
  Entry& slot(const FeatherBsdf& bsdf, std::size_t bin, const std::uint64_t* bits) {
    std::uint64_t h = splitmix(reinterpret_cast<std::uintptr_t>(&bsdf) ^ (bin * 0x9e3779b97f4a7c15ULL));
    for (int k = 0; k < 3; ++k) h = splitmix(h ^ bits[k]);
    return (*entries_)[h & (kSize - 1)];
  }
  static bool matches(const Entry& e, const FeatherBsdf& bsdf, std::size_t bin, const std::uint64_t* bits) {
    return e.bsdf == &bsdf && e.bin == bin && e.bits[0] == bits[0] && e.bits[1] == bits[1] && e.bits[2] == bits[2];
  }
  static void store(Entry& e, const FeatherBsdf& bsdf, std::size_t bin, const std::uint64_t* bits,
                    const FeatherBsdf::Incident& in) {
    e.bsdf = &bsdf;
    e.bin = bin;
    std::memcpy(e.bits, bits, sizeof e.bits);
    e.in = in;
  }

  static constexpr std::size_t kSize = 1024;
  static std::uint64_t splitmix(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
  }
  struct Entry {
    const FeatherBsdf* bsdf = nullptr;
    std::size_t bin = 0;
    std::uint64_t bits[3] = {0, 0, 0};
    FeatherBsdf::Incident in;
  };
  std::unique_ptr<std::array<Entry, kSize>> entries_;
  std::uint64_t hits_ = 0, misses_ = 0;
};

}  // namespace plumage::pathtracer
