// structure_generator "featherlab_files" (built into core, issue 25 (b)): cross sections read from
// the per-instance text files of FeatherLab's MATLAB generators (read_featherlab_instance,
// featherlab_section.hpp; docs/formats.md), e.g. a rock dove barbule (type 1):
//   structure: {generator: featherlab_files, instances: "data1/rockdove1Forest/geometry",
//               layers: [keratin, air, {mix: [air, melanin], fraction: 0.9}, keratin],
//               melanin_ratio_layer: 3}
// Instance n is file number n + first_number of the folder (FeatherLab numbers from 1); a folder
// with {index} names one folder per instance. Its parameters are declared once, in
// featherlab_file_params() (`plumage plugins describe featherlab_files`).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "geometry/instance_files.hpp"
#include "plumage/builtin_plugins.hpp"
#include "plumage/featherlab_section.hpp"
#include "plumage/input_file.hpp"
#include "plumage/param_table.hpp"
#include "plumage/structure_generator.hpp"

namespace plumage {

namespace {

struct FeatherLabFileParams {
  std::string instances;
  std::int64_t first_number = 1;
  double um_per_unit = 1.0;
  Material body = Material::keratin();
  std::vector<Material> layers;
  std::optional<std::size_t> melanin_ratio_layer;  // index into layers (the config counts from 1)
};

using FP = FeatherLabFileParams;

const ParamTable<FP>& featherlab_file_params() {
  static const auto table =
      ParamTable<FP>{}
          .text("instances", &FP::instances, required,
                "the folder of the FeatherLab geometry files (xyvalsN.txt, infoN.txt, melaninRatioN.txt), relative to "
                "the config's folder; {index} in it stands for the instance index n (one folder per instance)")
          .integer("first_number", &FP::first_number, "1", 1, Limits::closed(0, 1e9),
                   "instance n reads the files numbered n + first_number (FeatherLab's production scripts number "
                   "from 1)")
          .number("um_per_unit", &FP::um_per_unit, "um", 1.0, Limits::positive(),
                  "length of one coordinate unit of xyvals (FeatherLab writes um)")
          .custom("body", "material", "-", "keratin", "material of the barbule body (between top and bottom)",
                  [](const ParamView& p, FP& o) {
                    if (p.has("body")) o.body = parse_material(p, "body");
                  })
          .custom("layers", "list", "-", "required",
                  "material of each layer, top first: layer k lies between curve k and curve k + 1 of infoN.txt "
                  "(one fewer than the curves); values as any material (keratin, air, melanin, {n: 1.5, k: 0}, "
                  "{mix: [air, melanin], fraction: 0.9}, ...)",
                  [](const ParamView& p, FP& o) {
                    if (!p.has("layers")) p.fail("layers", "required: the material of each layer, top first");
                    for (const ParamView& m : p.items("layers")) o.layers.push_back(parse_material(m));
                    if (o.layers.empty()) p.fail("layers", "the list of layer materials is empty");
                  })
          .custom("melanin_ratio_layer", "integer", "1", "none",
                  "the layer (counted from 1 under the top; 2 or more) whose melanin fraction varies along the "
                  "barbule as melaninRatioN.txt gives it per top vertex; its material must be a mixture. Absent: "
                  "no melanin ratio file is read",
                  [](const ParamView& p, FP& o) {
                    if (!p.has("melanin_ratio_layer")) return;
                    const std::int64_t k = p.integer("melanin_ratio_layer", Limits::closed(2, 1e6));
                    if (static_cast<std::size_t>(k) > o.layers.size()) {
                      p.fail("melanin_ratio_layer", "layer " + std::to_string(k) + ", but `layers` lists " +
                                                        std::to_string(o.layers.size()));
                    }
                    if (o.layers[static_cast<std::size_t>(k - 1)].kind() != Material::Kind::mixture) {
                      p.fail("melanin_ratio_layer", "layer " + std::to_string(k) +
                                                        " is not a mixture ({mix: [host, melanin], fraction: f})");
                    }
                    o.melanin_ratio_layer = static_cast<std::size_t>(k - 1);
                  });
  return table;
}

class FeatherLabFile final : public StructureGenerator {
 public:
  FeatherLabFile(const ParamView& p, const PluginContext& ctx) {
    const FP o = featherlab_file_params().read(p);
    folders_ = InstanceFiles({o.instances}, ctx.config_dir, "featherlab_files");
    first_number_ = static_cast<std::uint64_t>(o.first_number);
    options_ = {o.um_per_unit, o.body, o.layers, o.melanin_ratio_layer};
    // A misspelt folder is refused at the config's `instances`, not at the first solve.
    try {
      const FeatherLabFiles f = featherlab_files_of(folders_.of(0), first_number_);
      check_input_file(f.xyvals, "FeatherLab xyvals");
      check_input_file(f.info, "FeatherLab info");
      if (o.melanin_ratio_layer) check_input_file(f.melanin_ratio, "FeatherLab melanin ratio");
    } catch (const InputFileError& e) {
      p.fail("instances", e.what());
    }
  }

  CrossSection generate(std::uint64_t index) const override {
    CrossSection cs = read_featherlab_instance(folders_.of(index), index + first_number_, options_);
    cs.generator = "featherlab_files";
    cs.instance = index;
    return cs;
  }

 private:
  InstanceFiles folders_;
  std::uint64_t first_number_ = 1;
  FeatherLabImportOptions options_;
};

}  // namespace

void register_featherlab_file(PluginRegistry& registry) {
  registry.builtin_registrar().add<StructureGenerator>(
      {.type = "featherlab_files",
       .version = "1.0.0",
       .summary = "cross sections read from FeatherLab's per-instance text files (xyvalsN, infoN, melaninRatioN; "
                  "layered barbules, types 1-3): instance n is file number n + first_number",
       .params = featherlab_file_params().specs()},
      [](const ParamView& p, const PluginContext& ctx) { return std::make_unique<FeatherLabFile>(p, ctx); });
}

}  // namespace plumage
