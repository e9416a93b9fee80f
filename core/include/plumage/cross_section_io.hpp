// Writing cross sections: the text format "plumage-cross-section 1" (docs/formats.md) and SVG
// pictures (white air, grey keratin, black melanin; mixtures shaded by melanin fraction).
#pragma once

#include "plumage/memory_budget.hpp"

#include <iosfwd>
#include <optional>
#include <utility>

#include "plumage/cross_section.hpp"
#include "plumage/image.hpp"

namespace plumage {

void write_cross_section_text(std::ostream& out, const CrossSection& section);

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
