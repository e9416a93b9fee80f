// FeatherLab's per-instance text files (featherlab_section.hpp) read into curves, before
// featherlab_section.cpp makes the two models of cross_section.hpp of them.
#pragma once

#include <vector>

#include "plumage/featherlab_section.hpp"

namespace plumage::featherlab_detail {

struct FeatherLabCurves {
  std::vector<Polyline> curves;       // nm, top first; each left → right, x strictly increasing
  std::vector<double> melanin_ratio;  // per top vertex but the two ends; empty when not read
};

// Refuses (InputFileError naming the file, line and field) what parse_featherlab_instance
// documents about the files themselves (everything but validate()'s verdict).
FeatherLabCurves read_featherlab_curves(const FeatherLabTexts& texts, const FeatherLabImportOptions& options);

}  // namespace plumage::featherlab_detail
