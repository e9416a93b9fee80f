// `plumage geometry` as a library: checked barbule instances of a structure generator, their
// files (.xsec text, .svg and .png pictures; docs/formats.md) and statistics of a set of them
// (widths, thickness, roughness and its correlation length, regularity, melanosomes, the mean
// local stack).
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "plumage/cross_section.hpp"
#include "plumage/structure_generator.hpp"

namespace plumage {

struct CheckedInstance {
  CrossSection section;
  double generate_ms = 0.0;            // wall time of generate() alone
  std::vector<std::string> problems;   // validate(section); empty when valid
};
// Instance `index` of `generator`, timed and checked for geometric validity.
CheckedInstance generate_checked(const StructureGenerator& generator, std::uint64_t index);
// Throws Error "<stem> instance <index> is geometrically invalid:" with one problem a line, when
// `instance` has problems (`plumage geometry` and plumage.cross_section without allow_invalid).
void refuse_invalid_instance(const CheckedInstance& instance, const std::string& stem, std::uint64_t index);

struct CrossSectionPictures {
  bool svg = true;
  bool png = true;
  double window_um = 0.0;  // > 0: draw only the central window of this width
  double pixels_per_um = 50.0;
};
// Refuses (MemoryBudgetError, exit status 2) pictures whose raster would not fit: callers check
// every instance before writing the first (write_cross_section_files checks its own too).
void check_cross_section_pictures(const CrossSection& section, const CrossSectionPictures& pictures);
// Writes <base>.xsec and the pictures asked for (<base>.svg, <base>.png), each atomically.
void write_cross_section_files(const CrossSection& section, const std::filesystem::path& base,
                               const CrossSectionPictures& pictures);

// Measured properties of a set of instances.
class GeometryStatistics {
 public:
  void add(const CrossSection& section);
  // The report `plumage geometry --stats` prints: "statistics of n instance(s) of <label>" and one
  // line per measured property (ranges with means; the mean stack under the central half).
  std::string report(const std::string& label, int instances) const;

 private:
  std::vector<double> width_um_, thickness_um_, rough_lo_, rough_hi_, corr_um_, regularity_lo_, regularity_hi_;
  std::vector<double> diameters_;
  std::map<std::string, int> roles_;
  // Stack under central nodes: per layer index, its material and the thickness at every node.
  std::vector<std::pair<std::string, std::vector<double>>> layers_;
};

}  // namespace plumage
