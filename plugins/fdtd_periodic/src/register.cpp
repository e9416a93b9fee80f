// Entry point of libplumage_fdtd_periodic.so.
//
// Provides:
//   table_builder "fdtd_periodic"   photonic-crystal reflection tables from the periodic 2.5D FDTD
//   accuracy_ladder "fdtd_periodic" resolution ladder vs the multilayer limit and vs the finest rung (ladder/, issue 9)
#include <cmath>
#include <optional>
#include <sstream>
#include <string_view>

#include "plumage/accuracy_ladder.hpp"
#include "plumage/error.hpp"
#include "plumage/plugin_export.hpp"
#include "table_build.hpp"

namespace {

using namespace plumage;

class FdtdTableBuilder final : public TableBuilder {
 public:
  FdtdTableBuilder(const ParamView& params, const PluginContext&) {
    static constexpr std::string_view kFidelity[] = {"preview", "production"};
    fidelity_ = params.choice_or("fidelity", kFidelity, "production");
    const bool preview = fidelity_ == "preview";
    // Unset: 15 nm (preview); production: the crystal's `fdtd: {resolution_nm}` or 10 nm.
    if (params.has("resolution_nm")) resolution_nm_ = params.number_or("resolution_nm", 10.0, Limits::positive());
    else if (preview) resolution_nm_ = 15.0;
    options_.k_step_per_um = params.number_or("k_step_per_um", preview ? 1.0 : 0.5, Limits::non_negative());
    options_.threads = static_cast<int>(params.integer_or("threads", 2, Limits::closed(1, 64)));
    options_.sim.pml_cells = static_cast<int>(params.integer_or("pml_cells", 24, Limits::closed(4, 200)));
    options_.sim.kz_min = params.number_or("kz_min", 0.25, Limits::closed(0.01, 0.9));
    options_.sim.dft_tol = params.number_or("dft_tol", 3e-4, Limits::positive());
    options_.sim.courant = params.number_or("courant", 0.95, Limits::closed(0.05, 1.0));
    options_.sim.smoothing = params.boolean_or("smoothing", true);
    // Unset: the crystal's own choice (crystal config `fdtd:` map, default off).
    if (params.has("dispersion_correction")) dispersion_correction_ = params.boolean_or("dispersion_correction", false);
    if (params.has("exact_fill")) exact_fill_ = params.boolean_or("exact_fill", false);
    if (params.has("grazing_anchors"))
      grazing_anchors_ = static_cast<int>(params.integer_or("grazing_anchors", 2, Limits::closed(1, 5)));
    options_.sim.substrate_below = params.number_or("substrate_below_um", 0.30, Limits::positive());
    options_.sim.air_above = params.number_or("air_above_um", 0.30, Limits::positive());
    options_.checkpoint = params.text_or("checkpoint", "");
  }

  static std::vector<ParamSpec> param_table() {
    return {
        {"fidelity", "text", "-", "production",
         "preview (15 nm grid, k step 1/um) or production (10 nm, 0.5/um)"},
        {"resolution_nm", "number", "nm", "by fidelity",
         "target grid step; cells per period = round(a_x/step) (preview 15; production: the crystal's fdtd: {resolution_nm} or 10)"},
        {"k_step_per_um", "number", "1/um", "by fidelity",
         "Bloch-k grid step of the broadband runs; 0 = one run per table entry with exact eps(lambda)"},
        {"threads", "integer", "1", "2", "worker threads (independent runs)"},
        {"pml_cells", "integer", "1", "24", "CPML thickness above and below"},
        {"kz_min", "number", "1", "0.25",
         "entries with cos(theta)cos(phi) below this are continued to the grazing limit (impedance form, NOTES.md 5a)"},
        {"grazing_anchors", "integer", "1", "the crystal's (fdtd: map; default 2)",
         "anchors per continued entry at k_z/k0 = kz_min + 0.01 + 0.05 m (Z polynomial in k_z^2 of degree anchors - 1)"},
        {"dft_tol", "number", "1", "3e-4", "stop when the reflected DFTs change by less than this"},
        {"courant", "number", "1", "0.95",
         "time step as a fraction of the Courant limit (>= 0.99 warns fdtd.courant: no stability margin)"},
        {"smoothing", "bool", "-", "true", "subpixel smoothing of material interfaces"},
        {"dispersion_correction", "bool", "-", "the crystal's (fdtd: map; default false)",
         "refit each material per run so the Yee grid's k_z is the exact one (NOTES.md 3a)"},
        {"exact_fill", "bool", "-", "the crystal's (fdtd: map; default false)",
         "fill fractions of mixed cells from exact circle chords (false: 8 x 8 point sample)"},
        {"substrate_below_um", "number", "um", "0.30", "keratin between the last row and the bottom PML"},
        {"air_above_um", "number", "um", "0.30", "air between the surface and the top PML"},
        {"checkpoint", "text", "-", "none", "file of finished runs: a rerun with the same cell and grid resumes from it"},
    };
  }

  ReflectionTable build(const CrystalCell& cell, const TableGrid& grid, Progress progress) const override {
    fdtd_table::Options o = options_;
    const double step_nm = resolution_nm_.value_or(cell.fdtd_resolution_nm > 0 ? cell.fdtd_resolution_nm : 10.0);
    o.nx = std::max(4, static_cast<int>(std::lround(cell.a_x_nm / step_nm)));
    o.sim.dispersion_correction = dispersion_correction_.value_or(cell.fdtd_dispersion_correction);
    o.sim.exact_fill = exact_fill_.value_or(cell.fdtd_exact_fill);
    o.grazing_anchors = grazing_anchors_.value_or(cell.fdtd_grazing_anchors);
    TableMetadata meta;
    meta.crystal = cell.name;
    meta.period_nm = cell.a_x_nm;
    meta.producer = "plumage fdtd_periodic 1.0.0 fidelity=" + fidelity_ +
                    " nx=" + std::to_string(o.nx) + " k_step=" + std::to_string(o.k_step_per_um) +
                    " engine=3 (bilinear Lorentz ADE, exact_fill " + (o.sim.exact_fill ? "on" : "off") + ", dispersion_correction " +
                    (o.sim.dispersion_correction ? "on" : "off") + ") grazing_anchors=" + std::to_string(o.grazing_anchors);
    std::ostringstream tag;
    tag.precision(17);
    tag << cell.name << ";" << static_cast<int>(cell.lattice) << ";" << cell.a_x_nm << ";" << cell.a_z_nm << ";"
        << cell.rod_diameter_nm << ";" << cell.core_diameter_nm << ";" << cell.channel_diameter_nm << ";"
        << cell.rows << ";" << cell.cortex_nm << ";" << cell.host.name() << ";" << cell.rod.name() << ";"
        << cell.core.name() << ";" << cell.channel.name() << ";" << o.sim.smoothing << ";" << o.sim.courant << ";"
        << o.sim.air_above << ";" << o.sim.substrate_below
        // engine revision 2: exact fill fractions + dispersion correction; revision 3: bilinear
        // Lorentz ADE (NOTES.md §3b). Runs of older revisions are not reused.
        << ";engine3;" << o.sim.dispersion_correction << ";" << o.sim.exact_fill << ";" << o.grazing_anchors;
    o.checkpoint_tag = tag.str();
    return fdtd_table::build_table(
        [&cell](double lambda_um) { return fdtd_table::cell_from_crystal(cell, lambda_um); },
        cell.a_x_nm * 1e-3, grid, meta, o, progress);
  }

 private:
  std::string fidelity_;
  std::optional<double> resolution_nm_;
  fdtd_table::Options options_;
  std::optional<bool> dispersion_correction_, exact_fill_;
  std::optional<int> grazing_anchors_;
};

class FdtdLadder final : public AccuracyLadder {
 public:
  explicit FdtdLadder(std::string crystal) : crystal_(std::move(crystal)) {}
  std::vector<LadderPoint> run(const Options& options) const override {
    return fdtd_table::run_fdtd_ladder(options, crystal_);
  }

 private:
  std::string crystal_;
};

void register_fdtd_periodic(Registrar& registrar) {
  registrar.add<TableBuilder>(
      {.kind = "",
       .type = "fdtd_periodic",
       .version = "1.0.0",
       .summary = "photonic-crystal reflection tables from a periodic 2.5D FDTD (Bloch k, CPML, "
                  "subpixel smoothing, dispersive melanin/keratin), Jones (s, p) per (lambda, theta, phi)",
       .params = FdtdTableBuilder::param_table()},
      [](const ParamView& params, const PluginContext& context) {
        return std::make_unique<FdtdTableBuilder>(params, context);
      });
  registrar.add<AccuracyLadder>(
      {.kind = "",
       .type = "fdtd_periodic",
       .version = "1.0.0",
       .summary = "accuracy ladder: grid steps 20-5 nm on a layered stack against the closed-form Airy "
                  "recursion, 15-3.8 nm on a crystal against its finest rung",
       .params = {{"crystal", "text", "-", "configs/crystals/mallard-green.yaml", "crystal cell of the second case"}}},
      [](const ParamView& params, const PluginContext&) {
        return std::make_unique<FdtdLadder>(params.text_or("crystal", "configs/crystals/mallard-green.yaml"));
      });
}

}  // namespace

PLUMAGE_PLUGIN(register_fdtd_periodic)
