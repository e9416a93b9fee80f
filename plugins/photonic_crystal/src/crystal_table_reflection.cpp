#include "crystal_table_reflection.hpp"

#include <filesystem>
#include <optional>

#include "plumage/diagnostics.hpp"
#include "plumage/error.hpp"
#include "plumage/param_table.hpp"
#include "plumage/table_build.hpp"

namespace plumage::photonic_crystal {

namespace fs = std::filesystem;

namespace {

using Tables = PreparationOptions::Tables;

// The reflection section as written (`model: photonic_crystal` and these).
struct TableReflectionParams {
  std::string table, crystal;  // exactly one
  std::string table_builder = "fdtd_periodic";
  std::optional<ParamView> builder;
  std::pair<double, double> lambda_nm{400.0, 700.0};
  // The production table grid (table_build.hpp), as `plumage table build --fidelity production`.
  int n_lambda = kProductionTableGrid.n_lambda, n_theta = kProductionTableGrid.n_theta, n_phi = kProductionTableGrid.n_phi;
};

fs::path resolve(const PluginContext& context, const std::string& name) {
  fs::path p(name);
  if (p.is_relative()) p = context.config_dir / p;
  return p.lexically_normal();
}

// The warnings a table's builder wrote into its notes ("WARNING: <text> [<code>]" items), as
// (code, "table <file>: <text>").
std::vector<std::pair<std::string, std::string>> table_warnings(const ReflectionTable& table, const std::string& file) {
  std::vector<std::pair<std::string, std::string>> out;
  const std::string& notes = table.metadata().notes;
  for (std::size_t at = notes.find("WARNING: "); at != std::string::npos; at = notes.find("WARNING: ", at + 1)) {
    const std::size_t open = notes.find(" [", at), close = notes.find(']', at);
    const std::size_t next = notes.find("; WARNING: ", at + 1);
    if (open == std::string::npos || close == std::string::npos || (next != std::string::npos && close > next)) continue;
    out.emplace_back(notes.substr(open + 2, close - open - 2), "table " + file + ": " + notes.substr(at + 9, open - at - 9));
  }
  return out;
}

const ParamTable<TableReflectionParams>& table_reflection_table() {
  using P = TableReflectionParams;
  const auto on_demand = [](const P& o) { return !o.crystal.empty(); };
  const std::string given = "crystal: given";
  static const auto table =
      ParamTable<P>{}
          .text("table", &P::table, "", "reflection table file (.plt, docs/formats.md); or give crystal:")
          .default_text("none")
          .text("crystal", &P::crystal, "",
                "crystal config (configs/crystals/*.yaml): its table built in the preparation step, cached by "
                "content hash")
          .default_text("none")
          .text("table_builder", &P::table_builder, "fdtd_periodic", "table_builder plug-in that builds the table")
          .only_if(on_demand, given)
          .custom("builder", "map", "-", "{}", "parameters of the table builder (e.g. fidelity: preview)",
                  [](const ParamView& p, P& o) {
                    if (p.has("builder")) o.builder = p.child("builder");
                  })
          .only_if(on_demand, given)
          .interval("lambda_nm", &P::lambda_nm, "nm", {400.0, 700.0}, Limits::positive(), "wavelength range of the table")
          .only_if(on_demand, given)
          .integer("n_lambda", &P::n_lambda, "1", kProductionTableGrid.n_lambda, Limits::closed(1, 10000), "wavelengths of the table")
          .only_if(on_demand, given)
          .integer("n_theta", &P::n_theta, "1", kProductionTableGrid.n_theta, Limits::closed(1, 10000), "cos theta nodes k/n (k = 1..n)")
          .only_if(on_demand, given)
          .integer("n_phi", &P::n_phi, "1", kProductionTableGrid.n_phi, Limits::closed(1, 10000), "cos phi_local nodes k/n (k = 1..n)")
          .only_if(on_demand, given);
  return table;
}

}  // namespace

std::vector<ParamSpec> CrystalTableReflection::param_table() { return table_reflection_table().specs(); }

CrystalTableReflection::CrystalTableReflection(const ParamView& params, const PluginContext& context) {
  const TableReflectionParams o = table_reflection_table().read(params);
  if (o.table.empty() == o.crystal.empty()) {
    params.fail_here("photonic_crystal: give exactly one of table: (a .plt file) or crystal: (a crystal config)");
  }
  if (!o.table.empty()) {
    // A given table file: loaded now (reading a file is no heavy work); nothing to prepare.
    table_file_ = resolve(context, o.table).string();
    table_ = ReflectionTable::load(table_file_);
    table_warnings_ = table_warnings(table_, table_file_);
    ready_.store(true, std::memory_order_release);
    return;
  }
  OnDemandRequest request;
  request.crystal_file = resolve(context, o.crystal);
  request.builder_type = o.table_builder;
  request.builder_params = o.builder;
  request.lambda_nm = o.lambda_nm;
  request.n_lambda = o.n_lambda;
  request.n_theta = o.n_theta;
  request.n_phi = o.n_phi;
  on_demand_ = std::make_unique<OnDemandTable>(request, context);
}

std::string CrystalTableReflection::pending_preparation() const {
  if (ready_.load(std::memory_order_acquire) || !on_demand_) return {};
  const std::string& file = on_demand_->file(false);
  if (fs::exists(file)) return "load the reflection table of " + on_demand_->describe(false) + " from " + file;
  return "build the reflection table of " + on_demand_->describe(false) + " into " + file;
}

[[noreturn]] void CrystalTableReflection::refuse(const std::string& why) const {
  throw Error("photonic_crystal: the reflection table of " + on_demand_->describe(false) + " (" +
              on_demand_->file(false) + ") " + why);
}

void CrystalTableReflection::make_ready(const PreparationOptions& options) const {
  const bool preview = options.tables == Tables::preview && on_demand_->preview_replaces();
  const std::string& file = on_demand_->file(preview);
  bool built = false;
  if (fs::exists(file)) {
    table_ = ReflectionTable::load(file);
  } else if (options.tables == Tables::never) {
    refuse("is not built, and the preparation option tables = never (--tables never) refuses to build it; build it "
           "once by running the same command with --tables build (the default; ~10-15 min on 2 cores for a "
           "production-size table, then cached), or give a built table as table:");
  } else {
    const std::string what = on_demand_->describe(preview);
    if (options.progress) {
      options.progress(0, 0,
                       "photonic_crystal: building the " + std::string(preview ? "preview " : "") + "reflection table of " +
                           what + " into " + file +
                           (on_demand_->entries(preview) >= 10000
                                ? "; a production-size table takes ~10-15 min on 2 cores, once (cached)"
                                : ""));
    }
    table_ = on_demand_->build(preview, options.progress);
    built = true;
  }
  table_file_ = file;
  preview_ = preview;
  table_warnings_ = table_warnings(table_, file);
  // A table built now: its builder raised its warnings while building.
  if (built) raised_on_build_ = true;
  ready_.store(true, std::memory_order_release);
}

void CrystalTableReflection::prepare(const PreparationOptions& options) const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!ready_.load(std::memory_order_acquire)) make_ready(options);
  if (!raised_on_build_) {
    for (const auto& [code, message] : table_warnings_) warn(code, message);
  }
  raised_on_build_ = false;
  if (preview_) {
    warn("photonic_crystal.preview_table",
         "reflection table of " + on_demand_->describe(false) + ": the preview table " + table_file_ + " (" +
             on_demand_->describe(true) + ", preparation option tables = preview: a test shortcut) stands in for " +
             on_demand_->file(false));
  }
}

const ReflectionTable& CrystalTableReflection::table() const {
  if (!ready_.load(std::memory_order_acquire)) {
    refuse("is not prepared: run the preparation step first (LocalReflection::prepare or prepare_species; the "
           "plumage commands do it before simulating)");
  }
  return table_;
}

void CrystalTableReflection::reflect(std::span<const Request> requests, std::span<JonesReflection> out) const {
  if (out.size() < requests.size()) throw Error("photonic_crystal: output span shorter than requests");
  const ReflectionTable& t = table();
  for (std::size_t i = 0; i < requests.size(); ++i) out[i] = t.query(requests[i].lambda_nm, requests[i].incidence);
}

}  // namespace plumage::photonic_crystal
