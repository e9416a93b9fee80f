// structure_generator "svg_file" (built into core, issue 25 (c)): cross sections traced over TEM
// images as SVG outlines (read_svg_cross_section, cross_section_io.hpp; docs/formats.md):
//   structure: {generator: svg_file, files: "tem/section-{index}.svg", um_per_unit: 0.001,
//               materials: {body: keratin, "#000000": melanin}}
// Instance n is the n-th file, as xsec_file's (instance_files.hpp). Its parameters are declared
// once, in svg_file_params() (`plumage plugins describe svg_file`).
#include <string>
#include <vector>

#include "geometry/instance_files.hpp"
#include "plumage/builtin_plugins.hpp"
#include "plumage/cross_section_io.hpp"
#include "plumage/input_file.hpp"
#include "plumage/param_table.hpp"
#include "plumage/structure_generator.hpp"

namespace plumage {

namespace {

struct SvgFileParams {
  std::vector<std::string> files;
  std::optional<double> um_per_unit;
  std::optional<double> scale_bar_um;
  std::vector<std::pair<std::string, Material>> materials;
  double max_segment_nm = 10.0;
};

const ParamTable<SvgFileParams>& svg_file_params() {
  static const auto table =
      ParamTable<SvgFileParams>{}
          .custom("files", "text or list", "-", "required",
                  "the SVG files, relative to the config's folder: a pattern in which {index} stands for the "
                  "instance index n (\"tem/section-{index}.svg\"), or a list whose n-th file is instance n",
                  [](const ParamView& p, SvgFileParams& o) { o.files = read_file_names(p, "the SVG files"); })
          .optional_number("um_per_unit", &SvgFileParams::um_per_unit, "um", "the scale bar's",
                           Limits::positive(), "length of one SVG user unit")
          .optional_number("scale_bar_um", &SvgFileParams::scale_bar_um, "um", "-", Limits::positive(),
                           "length of the element with id \"scale_bar\" (used without um_per_unit)")
          .custom("materials", "map", "-", "required",
                  "material of each outline: a key that begins its id (the longest such key wins), else a key "
                  "equal to its fill colour (quote it: \"#1a1a1a\"); values as any material (keratin, melanin, "
                  "air, {n: 1.5, k: 0}, ...)",
                  [](const ParamView& p, SvgFileParams& o) {
                    if (!p.has("materials")) p.fail("materials", "required: the material of each fill or id");
                    const ParamView m = p.child("materials");
                    for (const std::string& key : m.keys()) o.materials.emplace_back(key, parse_material(m, key));
                    if (o.materials.empty()) p.fail("materials", "no material given");
                  })
          .number("max_segment_nm", &SvgFileParams::max_segment_nm, "nm", 10.0, Limits::positive(),
                  "longest edge after import: traced edges are split evenly (the approximate solver's currents "
                  "live on the top's vertices)");
  return table;
}

class SvgFile final : public StructureGenerator {
 public:
  SvgFile(const ParamView& p, const PluginContext& ctx) {
    const SvgFileParams o = svg_file_params().read(p);
    files_ = InstanceFiles(o.files, ctx.config_dir, "svg_file");
    options_ = {o.um_per_unit, o.scale_bar_um, o.materials, o.max_segment_nm};
    try {
      for (std::size_t n = 0; n < files_.checked_count(); ++n) check_input_file(files_.of(n), "SVG cross section");
    } catch (const InputFileError& e) {
      p.fail("files", e.what());
    }
  }

  CrossSection generate(std::uint64_t index) const override {
    CrossSection cs = read_svg_cross_section(files_.of(index), options_);
    cs.generator = "svg_file";
    cs.instance = index;
    return cs;
  }

 private:
  InstanceFiles files_;
  SvgImportOptions options_;
};

}  // namespace

void register_svg_file(PluginRegistry& registry) {
  registry.builtin_registrar().add<StructureGenerator>(
      {.type = "svg_file",
       .version = "1.0.0",
       .summary = "cross sections traced as SVG outlines (paths of straight segments, polygons, rects) with a "
                  "material per id or fill: instance n is the n-th file",
       .params = svg_file_params().specs()},
      [](const ParamView& p, const PluginContext& ctx) { return std::make_unique<SvgFile>(p, ctx); });
}

}  // namespace plumage
