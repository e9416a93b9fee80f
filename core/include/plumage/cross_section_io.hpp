// Cross sections as files: the text format "plumage-cross-section 1" (docs/formats.md), written
// and read back exactly, and SVG / PNG pictures (white air, grey keratin, black melanin; mixtures
// shaded by melanin fraction).
#pragma once

#include "plumage/memory_budget.hpp"

#include <filesystem>
#include <iosfwd>
#include <string>
#include <string_view>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "plumage/cross_section.hpp"
#include "plumage/image.hpp"

namespace plumage {

// Every field of the section; numbers in their shortest exact form, so that reading the text
// back gives the same section bit for bit.
void write_cross_section_text(std::ostream& out, const CrossSection& section);

// The largest count (vertices, regions, boundaries...) a .xsec line may state: far above any
// plumage writes (a 2 mm barbule at 5 nm spacing has 4e5 top vertices), so that a damaged count
// is refused by name before the file's remaining bytes are even compared with it.
inline constexpr std::uint64_t kMaxCrossSectionCount = std::uint64_t{1} << 28;

// Reads what write_cross_section_text wrote (the file through InputFile, input_file.hpp).
// Refuses (InputFileError, "file: line N: what is wrong") a missing or non-regular file, a wrong
// header or version, a truncated file, a field that is not a finite number, a count over
// kMaxCrossSectionCount or over what the remaining bytes can hold (checked before allocating),
// an unknown role or material, indices out of range (a parent after its child, a bracket closing
// above itself), an open outline (a region of fewer than 3 vertices, or one that repeats its first
// vertex at its end), per-vertex lists of the wrong length and bytes after `end`. Geometric
// validity (self-intersections, nesting) is validate()'s (cross_section.hpp), as for generated
// sections.
CrossSection read_cross_section_text(const std::filesystem::path& file);
// The same from text in memory; `file` names it in the messages.
CrossSection parse_cross_section_text(std::string_view text, const std::string& file);

struct SvgOptions {
  double pixels_per_um = 50.0;
  // Only x in this window (nm) is drawn; default: the whole width.
  std::optional<std::pair<double, double>> window_nm;
  int max_columns = 600;  // reduced view: columns of layer stacks drawn at most
  bool exact = true;      // draw the exact regions (upper panel)
  bool reduced = true;    // draw the reduced model (lower panel, same x axis)
};

// Two panels stacked on one x axis: the exact regions above, the reduced model below (drawn as
// the layer stack along the normal of top vertices, as the approximate solver sees it).
void write_cross_section_svg(std::ostream& out, const CrossSection& section, const SvgOptions& options = {});

// The same two panels rasterised (scanline polygon fill; the reduced panel samples the stack
// along every top vertex's normal). Write it with write_png (image.hpp).
// Refuses (MemoryBudgetError) a picture whose raster would not fit (memory_budget.hpp).
Image render_cross_section(const CrossSection& section, const SvgOptions& options = {});
// The raster's memory (what render_cross_section checks first).
MemoryEstimate estimate_picture_memory(const CrossSection& section, const SvgOptions& options = {});
// Refuses (MemoryBudgetError, exit status 2) a picture over the PNG writer's 4 GiB raster limit,
// naming the --pixels-per-um that would fit.
void check_picture_size(const CrossSection& section, const SvgOptions& options = {});

}  // namespace plumage

namespace plumage {

// How an SVG traced over a TEM image becomes a cross section (read_svg_cross_section).
struct SvgImportOptions {
  // Length of one SVG user unit, µm; or, without it, the length of the element with id
  // "scale_bar" (a <line>, or the first-to-last point of a <path>/<polyline>) is `scale_bar_um`.
  std::optional<double> um_per_unit;
  std::optional<double> scale_bar_um;
  // Material of each outline: a key that is a prefix of the element's id (the longest wins),
  // else a key equal to its fill colour (attribute or style="fill:...", compared lower-case).
  std::vector<std::pair<std::string, Material>> materials;
  // Longest edge of the top, bottom and inner outlines after import, nm (edges are split evenly).
  double max_segment_nm = 10.0;
};

// An SVG (docs/formats.md, "Cross sections from SVG") as a cross section: every closed <path>
// (M L H V Z, absolute and relative), <polygon> and <rect> is a region; the largest is the body,
// the others nest by containment. y is flipped (z up), x centred on the body, z = 0 at its
// highest point. top / bottom are the body outline's chains above and below its leftmost and
// rightmost vertices. A layered model is made when every inner region spans the body's width (a
// layer); otherwise none (the label says so) and only the full-wave solver can use the section.
// Refuses (InputFileError, "file: element 'id' (line N): ...") an open outline, fewer than 3
// points, a curve or other unsupported path command, a transform, an outline with no material,
// and a file with no scale. Self-intersections and bad nesting are validate()'s.
CrossSection read_svg_cross_section(const std::filesystem::path& file, const SvgImportOptions& options);
CrossSection parse_svg_cross_section(std::string_view text, const std::string& file, const SvgImportOptions& options);

}  // namespace plumage
