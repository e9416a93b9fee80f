#include "settings.hpp"

#include <sstream>

namespace plumage::pathtracer {

const ParamTable<Settings>& settings_table() {
  using L = LevelOfDetail;
  static const auto table =
      ParamTable<Settings>{}
          .integer("spp", &Settings::samples_per_pixel, "1", 16, Limits::closed(1, 1 << 20),
                   "camera paths per pixel (box filter, uniform jitter)")
          .integer("seed", &Settings::seed, "1", 1, Limits::non_negative(),
                   "every random number is a pure function of (seed, pixel index, sample index)")
          .integer("max_depth", &Settings::max_depth, "vertices", 8, Limits::closed(1, 1000),
                   "surface vertices after the camera; next-event estimation still runs at the last one")
          .choice("lod", &Settings::lod, {{"auto", L::automatic}, {"mean", L::mean}, {"instance", L::instance}},
                  L::automatic,
                  "level of detail (DESIGN §7): auto = the mean BRDF where the ray cone's footprint covers >= "
                  "lod_barbules barbules, BRDF instance k = barbule id elsewhere; mean / instance force one")
          .number("lod_barbules", &Settings::lod_barbules, "barbules", 2.0, Limits::positive(),
                  "threshold of the automatic level of detail")
          .custom("lambda_nm", "interval", "nm", "[400, 700]",
                  "range of the hero wavelengths, both ends in [300, 1000], lo < hi",
                  [](const ParamView& p, Settings& s) {
                    if (!p.has("lambda_nm")) return;
                    const auto [lo, hi] = p.interval("lambda_nm", Limits::closed(300, 1000));
                    if (!(hi > lo)) p.fail("lambda_nm", "needs lo < hi");
                    s.lambda_min_nm = lo, s.lambda_max_nm = hi;
                  })
          .integer("spectral_bins", &Settings::spectral_bins, "1", 0, Limits::closed(0, 300),
                   "> 0: also return that many equal radiance bins over lambda_nm (EXR channels Sbb.lo-hinm)")
          .integer("tile_size", &Settings::tile_size, "px", 16, Limits::closed(1, 1024),
                   "oneTBB work unit; progress is reported per finished tile")
          .integer("threads", &Settings::threads, "1", 0, Limits::closed(0, 4096),
                   "> 0: a oneTBB arena of that many threads (0: all cores); images do not depend on it");
  return table;
}

std::string describe(const Settings& s) {
  std::ostringstream out;
  out << s.samples_per_pixel << " spp, lod "
      << (s.lod == LevelOfDetail::mean ? "mean" : s.lod == LevelOfDetail::instance ? "instance" : "auto") << ", seed "
      << s.seed;
  return out.str();
}

}  // namespace plumage::pathtracer
