// Checked instances and their files (plumage/instance_geometry.hpp).
#include <chrono>

#include "plumage/atomic_file.hpp"
#include "plumage/cross_section_io.hpp"
#include "plumage/error.hpp"
#include "plumage/image.hpp"
#include "plumage/instance_geometry.hpp"
#include "plumage/memory_budget.hpp"

namespace plumage {

CheckedInstance generate_checked(const StructureGenerator& generator, std::uint64_t index) {
  CheckedInstance out;
  const auto t0 = std::chrono::steady_clock::now();
  out.section = generator.generate(index);
  out.generate_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  out.problems = validate(out.section);
  return out;
}

void refuse_invalid_instance(const CheckedInstance& instance, const std::string& stem, std::uint64_t index) {
  if (instance.problems.empty()) return;
  std::string msg = stem + " instance " + std::to_string(index) + " is geometrically invalid:";
  for (const auto& p : instance.problems) msg += "\n  " + p;
  throw Error(msg);
}

namespace {
SvgOptions svg_options(const CrossSectionPictures& pictures) {
  SvgOptions options;
  options.pixels_per_um = pictures.pixels_per_um;
  if (pictures.window_um > 0) options.window_nm = std::make_pair(-500.0 * pictures.window_um, 500.0 * pictures.window_um);
  return options;
}
}  // namespace

void check_cross_section_pictures(const CrossSection& section, const CrossSectionPictures& pictures) {
  if (!pictures.png) return;
  check_picture_size(section, svg_options(pictures));
  check_memory(estimate_picture_memory(section, svg_options(pictures)));
}

void write_cross_section_files(const CrossSection& section, const std::filesystem::path& base,
                               const CrossSectionPictures& pictures) {
  check_cross_section_pictures(section, pictures);
  write_file_atomically(base.string() + ".xsec", [&](std::ostream& s) { write_cross_section_text(s, section); });
  const SvgOptions options = svg_options(pictures);
  if (pictures.svg) {
    write_file_atomically(base.string() + ".svg", [&](std::ostream& s) { write_cross_section_svg(s, section, options); });
  }
  if (pictures.png) {
    // A wide barbule's picture is the long step of `plumage geometry` (seconds per 1e8 pixels
    // drawn and encoded): say which one is being drawn (plumage/memory_budget.hpp, report_step).
    const MemoryEstimate e = estimate_picture_memory(section, options);
    if (e.total_bytes() > 1e8) report_step("geometry: drawing " + base.filename().string() + ".png", 0, 0, e.job);
    write_png(render_cross_section(section, options), base.string() + ".png");
  }
}

}  // namespace plumage
