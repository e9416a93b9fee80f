// The files of one render (render_job.hpp): EXR radiance + PNG preview, together or not at all.
#include <filesystem>
#include <map>
#include <string>

#include "plumage/atomic_file.hpp"
#include "plumage/diagnostics.hpp"
#include "plumage/exr.hpp"
#include "plumage/image.hpp"
#include "plumage/render_job.hpp"

namespace plumage {

namespace fs = std::filesystem;

void write_render_images(const RenderResult& r, double png_exposure, const fs::path& exr, const fs::path& png) {
  const fs::path tmp_exr = fs::path(exr).concat(".partial.exr"), tmp_png = fs::path(png).concat(".partial.png");
  bool exr_in_place = false;
  check_output_path(exr);
  check_output_path(png);
  try {
    // The run's warnings (plumage/diagnostics.hpp: materials' own warnings included) travel with
    // the image.
    std::map<std::string, std::string> attributes;
    if (!diagnostics().empty()) attributes["plumage:warnings"] = diagnostics().summary();
    write_exr(r.rgb, tmp_exr, r.spectral.bins > 0 ? &r.spectral : nullptr, attributes);
    LinearImage scaled = r.rgb;
    const float e = static_cast<float>(png_exposure);
    for (RgbF& p : scaled.pixels()) p = {p.r * e, p.g * e, p.b * e};
    write_png(to_display(scaled), tmp_png);
    // Checked again at the rename (rename(2) would replace a symlink or device put there meanwhile).
    check_output_path(exr);
    check_output_path(png);
    fs::rename(tmp_exr, exr);
    exr_in_place = true;
    fs::rename(tmp_png, png);
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp_exr, ec);
    fs::remove(tmp_png, ec);
    if (exr_in_place) fs::remove(exr, ec);  // not one without the other
    throw;
  }
}

}  // namespace plumage
