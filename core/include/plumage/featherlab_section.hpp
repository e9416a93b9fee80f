// Cross sections from FeatherLab's per-instance text files (issue 25 (b); docs/formats.md,
// "Cross sections from FeatherLab files"): the MATLAB generators of the paper's code write, for
// instance number N of a barbule type, a folder's
//   xyvalsN.txt        "x,y" per line (µm): the vertices of every curve, one curve after another
//   infoN.txt          "start,count" per line: curve k is rows start .. start + count - 1 of xyvals
//   melaninRatioN.txt  one melanin fraction per line: a value per top vertex but the two ends
// plumage reads the layered form of these files (barbule types 1-3: open curves top to bottom,
// the first the top surface, the last the bottom surface) into both of its models: the layered
// model (cross_section.hpp: the curves as layer boundaries, with the material of each layer from
// the config) and the region model (the body and a band between two curves per layer whose
// material is not the body's).
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "plumage/cross_section.hpp"

namespace plumage {

struct FeatherLabImportOptions {
  // Length of one coordinate unit of xyvals, µm (FeatherLab writes µm).
  double um_per_unit = 1.0;
  // Material of the barbule body (the region whose outline is the top and the bottom curve).
  Material body = Material::keratin();
  // The medium between curve k and curve k + 1, top first: one fewer than the curves.
  std::vector<Material> layers;
  // The layer (index into `layers`, ≥ 1: not the one under the top) whose guest fraction varies
  // along the barbule as melaninRatioN.txt says; its material must be a mixture. Unset: the
  // melanin ratio file is not read.
  std::optional<std::size_t> melanin_ratio_layer;
};

// The three files of one instance, and their text (what read_featherlab_instance reads).
struct FeatherLabTexts {
  std::string xyvals, info, melanin_ratio;                 // melanin_ratio empty when not read
  std::string xyvals_name, info_name, melanin_ratio_name;  // named in the messages
};

// The files of instance `number` in `folder`: xyvals<number>.txt, info<number>.txt,
// melaninRatio<number>.txt.
struct FeatherLabFiles {
  std::filesystem::path xyvals, info, melanin_ratio;
};
FeatherLabFiles featherlab_files_of(const std::filesystem::path& folder, std::uint64_t number);

// The largest number of vertices (rows of xyvals) an instance may have: far above FeatherLab's
// (a 25 µm barbule at 30 nm spacing has about 6 000 over all curves), so that a damaged count is
// refused by name before anything is allocated for it.
inline constexpr std::size_t kMaxFeatherLabVertices = std::size_t{1} << 24;

// Reads one instance (the files through InputFile, input_file.hpp). Refuses (InputFileError,
// "file: line N: what is wrong", naming the field) a missing file, a field that is not a finite
// number, a row of the wrong number of fields, counts that do not tile xyvals (a first start
// other than 0, a gap, an overlap, a total other than the rows of xyvals), fewer than 2 curves,
// a curve of fewer than 2 vertices, a closed curve (a melanosome or bubble outline: the
// non-layered types 4-7 are not read), a top whose x is not strictly monotone (a curve written
// right to left is turned round, the melanin ratio with the top),
// a number of curves other than `layers` + 1, a melanin ratio file of a length other than the
// top's vertices - 2 or with a value outside [0, 1], and a section that validate()
// (cross_section.hpp: self-intersecting or crossing curves, regions outside the body) refuses.
CrossSection parse_featherlab_instance(const FeatherLabTexts& texts, const FeatherLabImportOptions& options);
CrossSection read_featherlab_instance(const FeatherLabFiles& files, const FeatherLabImportOptions& options);
CrossSection read_featherlab_instance(const std::filesystem::path& folder, std::uint64_t number,
                                      const FeatherLabImportOptions& options);

}  // namespace plumage
