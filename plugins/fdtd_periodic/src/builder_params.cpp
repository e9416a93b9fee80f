#include "builder_params.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>


namespace plumage::fdtd_table {

namespace {

using Fidelity = BuilderParams::Fidelity;

// grazing_anchors has no default of its own (unset: the crystal's), which the generic integer
// row cannot express: read here, range [1, 5] as in the crystal section.
void read_grazing_anchors(const ParamView& p, BuilderParams& o) {
  if (p.has("grazing_anchors"))
    o.grazing_anchors = static_cast<int>(p.integer_or("grazing_anchors", 2, Limits::closed(1, 5)));
}

constexpr const char* kAnchorsDoc =
    "anchors per continued entry at k_z/k0 = kz_min + 0.01 + 0.05 m (Z polynomial in k_z^2 of degree anchors - 1), "
    "in [1, 5]";

}  // namespace

const ParamTable<BuilderParams>& builder_params() {
  using P = BuilderParams;
  static const auto table =
      ParamTable<P>{}
          .choice("fidelity", &P::fidelity, {{"preview", Fidelity::preview}, {"production", Fidelity::production}},
                  Fidelity::production, "preview (15 nm grid, k step 1/um) or production (10 nm, 0.5/um)")
          .optional_number("resolution_nm", &P::resolution_nm, "nm", "by fidelity", Limits::positive(),
                           "target grid step; cells per period = round(a_x/step) (preview 15; production: the "
                           "crystal's fdtd_periodic: {resolution_nm} or 10)")
          .optional_number("k_step_per_um", &P::k_step_per_um, "1/um", "by fidelity (preview 1, production 0.5)",
                           Limits::non_negative(),
                           "Bloch-k grid step of the broadband runs; 0 = one run per table entry with exact eps(lambda)")
          .integer("threads", &P::threads, "1", 2, Limits::closed(1, 64), "worker threads (independent runs)")
          .integer("pml_cells", &P::pml_cells, "1", 24, Limits::closed(4, 200), "CPML thickness above and below")
          .number("kz_min", &P::kz_min, "1", 0.25, Limits::closed(0.01, 0.9),
                  "entries with cos(theta)cos(phi) below this are continued to the grazing limit (impedance form, "
                  "NOTES.md 5a)")
          .custom("grazing_anchors", "integer", "1", "the crystal's (fdtd_periodic: section; default 2)", kAnchorsDoc,
                  read_grazing_anchors)
          .number("dft_tol", &P::dft_tol, "1", 3e-4, Limits::positive(),
                  "stop when the reflected DFTs change by less than this")
          .number("courant", &P::courant, "1", 0.95, Limits::closed(0.05, 1.0),
                  "time step as a fraction of the Courant limit (>= 0.99 warns fdtd.courant: no stability margin)")
          .boolean("smoothing", &P::smoothing, true, "subpixel smoothing of material interfaces")
          .optional_boolean("dispersion_correction", &P::dispersion_correction,
                            "the crystal's (fdtd_periodic: section; default false)",
                            "refit each material per run so the Yee grid's k_z is the exact one (NOTES.md 3a)")
          .optional_boolean("exact_fill", &P::exact_fill, "the crystal's (fdtd_periodic: section; default false)",
                            "fill fractions of mixed cells from exact circle chords (false: 8 x 8 point sample)")
          .number("substrate_below_um", &P::substrate_below_um, "um", 0.30, Limits::positive(),
                  "keratin between the last row and the bottom PML")
          .number("air_above_um", &P::air_above_um, "um", 0.30, Limits::positive(),
                  "air between the surface and the top PML")
          .text("checkpoint", &P::checkpoint, "",
                "file of finished runs: a rerun with the same cell and grid resumes from it (empty: none)");
  return table;
}

const ParamTable<CrystalNumerics>& crystal_numerics_params() {
  using C = CrystalNumerics;
  static const auto table =
      ParamTable<C>{}
          .boolean("dispersion_correction", &C::dispersion_correction, false,
                   "refit each material per run so the Yee grid's k_z is the exact one (NOTES.md 3a)")
          .boolean("exact_fill", &C::exact_fill, false,
                   "fill fractions of mixed cells from exact circle chords and Gauss rows (false: 9 probes and an "
                   "8 x 8 point sample)")
          .optional_number("resolution_nm", &C::resolution_nm, "nm", "the builder's (10)", Limits::positive(),
                           "production grid step of this crystal")
          .optional_number("k_step_per_um", &C::k_step_per_um, "1/um", "the builder's (0.5)", Limits::positive(),
                           "production Bloch-k grid step of this crystal (thin shells: 0.25, rcwa NOTES.md §4)")
          .integer("grazing_anchors", &C::grazing_anchors, "1", 2, Limits::closed(1, 5), kAnchorsDoc);
  return table;
}


CrystalNumerics crystal_numerics(const CrystalCell& cell) {
  const auto it = cell.builder_sections.find("fdtd_periodic");
  if (it == cell.builder_sections.end()) return crystal_numerics_params().defaults();
  const CrystalNumerics n = crystal_numerics_params().read(it->second);
  it->second.finish();
  return n;
}

BuildPlan plan_build(const BuilderParams& p, const CrystalCell& cell) {
  const bool preview = p.fidelity == Fidelity::preview;
  const CrystalNumerics numerics = crystal_numerics(cell);
  BuildPlan plan;
  Options& o = plan.options;
  o.k_step_per_um = p.k_step_per_um.value_or(preview ? 1.0 : numerics.k_step_per_um.value_or(0.5));
  o.threads = p.threads;
  o.sim.pml_cells = p.pml_cells;
  o.sim.kz_min = p.kz_min;
  o.sim.dft_tol = p.dft_tol;
  o.sim.courant = p.courant;
  o.sim.smoothing = p.smoothing;
  o.sim.substrate_below = p.substrate_below_um;
  o.sim.air_above = p.air_above_um;
  o.checkpoint = p.checkpoint;
  // Unset: 15 nm (preview); production: the crystal's resolution_nm or 10 nm.
  const double step_nm = p.resolution_nm.value_or(preview ? 15.0 : numerics.resolution_nm.value_or(10.0));
  o.nx = std::max(4, static_cast<int>(std::lround(cell.a_x_nm / step_nm)));
  o.sim.dispersion_correction = p.dispersion_correction.value_or(numerics.dispersion_correction);
  o.sim.exact_fill = p.exact_fill.value_or(numerics.exact_fill);
  o.grazing_anchors = p.grazing_anchors.value_or(numerics.grazing_anchors);
  TableMetadata& meta = plan.meta;
  meta.crystal = cell.name;
  meta.period_nm = cell.a_x_nm;
  meta.producer = std::string("plumage fdtd_periodic ") + kPluginVersion + " fidelity=" + (preview ? "preview" : "production") +
                  " nx=" + std::to_string(o.nx) + " k_step=" + std::to_string(o.k_step_per_um) +
                  " engine=3 (bilinear Lorentz ADE, exact_fill " + (o.sim.exact_fill ? "on" : "off") +
                  ", dispersion_correction " + (o.sim.dispersion_correction ? "on" : "off") +
                  ") grazing_anchors=" + std::to_string(o.grazing_anchors);
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
  return plan;
}

}  // namespace plumage::fdtd_table
