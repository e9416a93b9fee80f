// structure_generator "xsec_file" (built into core, issue 25 (a)): cross sections imported from
// plumage's own .xsec files (what `plumage geometry` writes), so any species config can simulate
// a measured or edited section like a procedural one:
//   structure: {generator: xsec_file, files: "rd/rockdove-forest-{index}.xsec"}
// Its parameters are declared once, in xsec_file_params() (`plumage plugins describe xsec_file`).
//
// Instance n is the file the pattern names with {index} = n (or the n-th of a list), read by
// read_cross_section_text exactly as written: the same top, regions, reduced model, crystal
// reference, label and seed, so a section written and imported gives the far field of the
// instance that was written. Its geometric validity is checked where every generated section's
// is (validate(), by `plumage geometry`, simulate, ...).
#include <filesystem>
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

struct XsecFileParams {
  std::vector<std::string> files;  // one pattern with {index}, or the files of instances 0, 1, ...
};

const ParamTable<XsecFileParams>& xsec_file_params() {
  static const auto table = ParamTable<XsecFileParams>{}.custom(
      "files", "text or list", "-", "required",
      "the .xsec files (plumage-cross-section 1, as `plumage geometry` writes them), relative to the config's "
      "folder: a pattern in which {index} stands for the instance index n (\"rd/rockdove-forest-{index}.xsec\"), "
      "or a list whose n-th file is instance n",
      [](const ParamView& p, XsecFileParams& o) { o.files = read_file_names(p, "the .xsec files"); });
  return table;
}

class XsecFile final : public StructureGenerator {
 public:
  XsecFile(const ParamView& p, const PluginContext& ctx) : files_(xsec_file_params().read(p).files, ctx.config_dir, "xsec_file") {
    // A misspelt folder or pattern is refused at the config's `files`, not at the first solve.
    try {
      for (std::size_t n = 0; n < files_.checked_count(); ++n) check_input_file(files_.of(n), "cross section");
    } catch (const InputFileError& e) {
      p.fail("files", e.what());
    }
  }

  CrossSection generate(std::uint64_t index) const override { return read_cross_section_text(files_.of(index)); }

 private:
  InstanceFiles files_;
};

}  // namespace

void register_xsec_file(PluginRegistry& registry) {
  registry.builtin_registrar().add<StructureGenerator>(
      {.type = "xsec_file",
       .version = "1.0.0",
       .summary = "cross sections read from .xsec files (plumage-cross-section 1, as `plumage geometry` writes "
                  "them): instance n is the n-th file",
       .params = xsec_file_params().specs()},
      [](const ParamView& p, const PluginContext& ctx) { return std::make_unique<XsecFile>(p, ctx); });
}

}  // namespace plumage
