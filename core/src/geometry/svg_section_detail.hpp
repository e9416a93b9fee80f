// The SVG subset's outlines in the drawing's own units, y down (svg_section.cpp), before
// svg_section_model.cpp turns them into a CrossSection.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "plumage/cross_section.hpp"

namespace plumage::svg_detail {

struct SvgOutline {
  std::string id;     // may be empty
  std::string fill;   // lower-case, as written ("#4d4d4d", "black"); empty when none
  std::string where;  // "element 'id' (line N)" for messages
  std::vector<Vec2> points;  // x, y in SVG user units (Vec2::z holds y, downward)
  bool closed = false;
};

struct SvgDrawing {
  std::vector<SvgOutline> outlines;      // closed, ≥ 3 points, in document order
  std::optional<double> scale_bar_units;  // length of the element with id "scale_bar"
};

// Refuses (InputFileError naming the element) what read_svg_cross_section documents.
SvgDrawing read_svg_drawing(std::string_view text, const std::string& file);

}  // namespace plumage::svg_detail
