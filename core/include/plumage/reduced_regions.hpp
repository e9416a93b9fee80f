// The reduced layered model of a barbule (CrossSection::layered) as closed region polygons, so
// that a full-wave solver can simulate exactly the layers the approximate solver sees ("full-wave
// on the reduced layer geometry", paper §6.1, Fig. 8).
//
// Construction, for the boundaries b_0 … b_{N−1} (top → bottom) of a LayeredModel:
//  * region 0 is the body, band_polygon(top, bottom), with the material under the top surface
//    (`below_top`, the cortex) — the same outline as the exact model;
//  * at the outer level, consecutive boundaries b_i, b_j (j the next boundary after i that is
//    not inside a bracket) enclose a layer of material b_i.below: the band between them, both
//    clipped to their common x range, becomes a region (child of the body) unless its material
//    is the body's (then the body already holds it) or it lies below the last boundary (air);
//  * a bracket [i, closes] (a hummingbird platelet) becomes one region, the band between b_i
//    and b_closes with material b_i.below; the layers between the bracket's inner boundaries
//    become its children unless they have the bracket's material. Brackets nest.
//
// Differences from what the approximate solver computes along a top-surface normal
// (layer_profile_at), both confined to the ends of boundaries:
//  * a normal line that misses a boundary extends the boundary's end segment; here a layer ends
//    where the shorter of its two boundaries ends (closed by a straight segment);
//  * mixtures with a per-vertex guest fraction (granular layers, mixed cores) get one fraction
//    per region: the mean of the per-vertex fractions of the boundary above (`mean`, default),
//    or, with `piecewise`, the band is cut into slabs of `piece_nm` in x, each with the mean
//    fraction of the vertices inside it (adjacent slabs share their cut vertices exactly).
// Lengths in nm.
#pragma once

#include <vector>

#include "plumage/cross_section.hpp"

namespace plumage {

struct ReducedRegionOptions {
  enum class Mixture { mean, piecewise };
  Mixture mixture = Mixture::mean;
  double piece_nm = 1000.0;  // slab width for Mixture::piecewise
};

// The regions of the reduced model (region 0 the body). Throws Error if the section has no
// layered model (crystal-type barbules, validation shapes).
std::vector<Region> reduced_regions(const CrossSection& section, const ReducedRegionOptions& options = {});

// A copy of `section` whose `regions` are the reduced ones (top, bottom and the layered model
// unchanged, so the approximate solver sees the same section); label gets " (reduced layers)".
CrossSection with_reduced_regions(const CrossSection& section, const ReducedRegionOptions& options = {});

}  // namespace plumage
