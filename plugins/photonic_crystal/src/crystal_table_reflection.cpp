#include "crystal_table_reflection.hpp"

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <fstream>
#include <iterator>
#include <sstream>

#include "plumage/config_document.hpp"
#include "plumage/crystal_cell.hpp"
#include "plumage/diagnostics.hpp"
#include "plumage/error.hpp"
#include "plumage/plugin_registry.hpp"
#include "plumage/table_builder.hpp"

namespace plumage::photonic_crystal {

namespace fs = std::filesystem;

namespace {

fs::path resolve(const PluginContext& context, const std::string& name) {
  fs::path p(name);
  if (p.is_relative()) p = context.config_dir / p;
  return p.lexically_normal();
}

std::string read_bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error("photonic_crystal: cannot read " + file.string());
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Flat text of a (possibly nested) parameter map, in file order: part of the cache key.
void flatten(const ParamView& v, std::ostringstream& os) {
  if (v.is_map()) {
    for (const auto& k : v.keys()) {
      os << k << "{";
      flatten(v.node(k), os);
      os << "}";
    }
  } else if (v.is_sequence()) {
    for (const auto& item : v.items()) {
      os << "[";
      flatten(item, os);
      os << "]";
    }
  } else if (!v.is_null()) {
    os << v.scalar_text();
  }
}

}  // namespace

std::vector<ParamSpec> CrystalTableReflection::param_table() {
  return {
      {"table", "text", "-", "-", "reflection table file (.plt, docs/formats.md); or give crystal:"},
      {"crystal", "text", "-", "-", "crystal config (configs/crystals/*.yaml): build the table on demand, cached by content hash"},
      {"table_builder", "text", "-", "fdtd_periodic", "table_builder plug-in used with crystal:"},
      {"builder", "map", "-", "{}", "parameters of the table builder (e.g. fidelity: preview)"},
      {"lambda_nm", "interval", "nm", "[400, 700]", "wavelength range of an on-demand table"},
      {"n_lambda", "integer", "1", "50", "wavelengths of an on-demand table"},
      {"n_theta", "integer", "1", "20", "cos theta nodes k/n (k = 1..n) of an on-demand table"},
      {"n_phi", "integer", "1", "50", "cos phi_local nodes k/n (k = 1..n) of an on-demand table"},
  };
}

namespace {

// A table built with warnings ("WARNING: <text> [<code>]" items in its notes, written by the
// builder) passes them on to every run that uses it, so a material or image made with it
// carries them too (issue 9).
void raise_table_warnings(const ReflectionTable& table, const std::string& file) {
  const std::string& notes = table.metadata().notes;
  for (std::size_t at = notes.find("WARNING: "); at != std::string::npos; at = notes.find("WARNING: ", at + 1)) {
    const std::size_t open = notes.find(" [", at), close = notes.find(']', at);
    const std::size_t next = notes.find("; WARNING: ", at + 1);
    if (open == std::string::npos || close == std::string::npos || (next != std::string::npos && close > next)) continue;
    warn(notes.substr(open + 2, close - open - 2), "table " + file + ": " + notes.substr(at + 9, open - at - 9));
  }
}

}  // namespace

CrystalTableReflection::CrystalTableReflection(const ParamView& params, const PluginContext& context) {
  const bool has_table = params.has("table"), has_crystal = params.has("crystal");
  if (has_table == has_crystal)
    throw Error("photonic_crystal: give exactly one of table: (a .plt file) or crystal: (a crystal config)");
  if (has_table) {
    const fs::path file = resolve(context, params.text("table"));
    table_ = ReflectionTable::load(file);
    table_file_ = file.string();
    raise_table_warnings(table_, table_file_);
    std::call_once(ready_, [] {});
    return;
  }
  // On demand: build with the table builder, cached under <cache>/tables/<key>.plt.
  const fs::path crystal_file = resolve(context, params.text("crystal"));
  const std::string builder_type = params.text_or("table_builder", "fdtd_periodic");
  const auto [lo, hi] = params.has("lambda_nm") ? params.interval("lambda_nm", Limits::positive())
                                                : std::pair<double, double>{400.0, 700.0};
  const int nl = static_cast<int>(params.integer_or("n_lambda", 50, Limits::closed(1, 10000)));
  const int nt = static_cast<int>(params.integer_or("n_theta", 20, Limits::closed(1, 10000)));
  const int np = static_cast<int>(params.integer_or("n_phi", 50, Limits::closed(1, 10000)));
  const ParamView builder_params = params.has("builder") ? params.child("builder") : ParamView{};
  cell_ = load_crystal_cell(crystal_file);  // validates the crystal now (file:line:col errors)
  crystal_file_ = crystal_file.string();
  config_hash_ = fnv1a_hex(read_bytes(crystal_file));
  std::ostringstream key;
  key << "crystal=" << config_hash_ << ";builder=" << builder_type << ";";
  if (params.has("builder")) flatten(builder_params, key);
  key << ";grid=" << lo << "," << hi << "," << nl << "," << nt << "," << np;
  const fs::path cache = context.cache_dir.empty() ? fs::path("build/cache") : context.cache_dir;
  const std::string stem = crystal_file.stem().string();
  table_file_ = (cache / "tables" / (stem + "-" + fnv1a_hex(key.str()) + ".plt")).string();
  grid_ = TableGrid::uniform(lo, hi, nl, nt, np);
  if (fs::exists(table_file_)) {
    table_ = ReflectionTable::load(table_file_);
    raise_table_warnings(table_, table_file_);
    std::call_once(ready_, [] {});
    return;
  }
  if (!context.registry)
    throw Error("photonic_crystal: building " + table_file_ + " needs the plug-in registry");
  builder_ = context.registry->create_named<TableBuilder>(builder_type, builder_params, context);
  // The preview variant (PLUMAGE_TABLE_BUILD=preview): the builder's preview fidelity on a
  // 4 λ × 5 cos θ × 5 cos φ grid over the same λ range, cached under its own key.
  const ConfigDocument preview_doc = ConfigDocument::parse("fidelity: preview\n", "PLUMAGE_TABLE_BUILD=preview");
  preview_builder_ = context.registry->create_named<TableBuilder>(builder_type, preview_doc.root(), context);
  std::ostringstream pkey;
  pkey << "crystal=" << config_hash_ << ";builder=" << builder_type << ";fidelity{preview};grid=" << lo << ","
       << hi << ",4,5,5";
  preview_file_ = (cache / "tables" / (stem + "-preview-" + fnv1a_hex(pkey.str()) + ".plt")).string();
}

void CrystalTableReflection::build_or_load() const {
  std::call_once(ready_, [this] {
    // Under CTest (it sets CTEST_INTERACTIVE_DEBUG_MODE for every test it runs) the default is
    // "preview": the default test suite never starts a production table build.
    const char* env = std::getenv("PLUMAGE_TABLE_BUILD");
    const std::string policy = env ? env : (std::getenv("CTEST_INTERACTIVE_DEBUG_MODE") ? "preview" : "build");
    if (policy == "never")
      throw Error("photonic_crystal: reflection table " + table_file_ + " of " + crystal_file_ +
                  " is not built and PLUMAGE_TABLE_BUILD=never; build it by running once without "
                  "that setting (or use `plumage table build` and give the file as table:)");
    // preview replaces only builds larger than the preview grid (4 × 5 × 5); smaller ones run as asked.
    const bool preview =
        policy == "preview" && grid_.lambda_nm.size() * grid_.cos_theta.size() * grid_.cos_phi.size() > 4 * 5 * 5;
    if (policy != "preview" && policy != "build")
      throw Error("photonic_crystal: PLUMAGE_TABLE_BUILD must be build, preview or never (got '" + policy + "')");
    const fs::path file = preview ? preview_file_ : table_file_;
    if (fs::exists(file)) {
      table_ = ReflectionTable::load(file);
      raise_table_warnings(table_, file.string());
      return;
    }
    const TableGrid grid = preview ? TableGrid::uniform(grid_.lambda_nm.front(), grid_.lambda_nm.back(), 4, 5, 5) : grid_;
    std::cerr << "photonic_crystal: building the " << (preview ? "preview " : "") << "reflection table of "
              << cell_.name << " (" << grid.lambda_nm.size() << " x " << grid.cos_theta.size() << " x "
              << grid.cos_phi.size() << " entries) into " << file.string()
              << (grid.lambda_nm.size() * grid.cos_theta.size() * grid.cos_phi.size() >= 10000
                      ? "; a production-size table takes ~10-15 min on 2 cores, once (cached)"
                      : "")
              << "\n";
    ReflectionTable t = (preview ? preview_builder_ : builder_)->build(cell_, grid, {});
    t.metadata().config_hash = config_hash_;
    fs::create_directories(file.parent_path());
    t.save(file);  // atomic (ReflectionTable::save)
    table_ = std::move(t);
  });
}

const ReflectionTable& CrystalTableReflection::table() const {
  build_or_load();
  return table_;
}

void CrystalTableReflection::reflect(std::span<const Request> requests, std::span<JonesReflection> out) const {
  if (out.size() < requests.size()) throw Error("photonic_crystal: output span shorter than requests");
  const ReflectionTable& t = table();
  for (std::size_t i = 0; i < requests.size(); ++i)
    out[i] = t.query(requests[i].lambda_nm, requests[i].incidence);
}

}  // namespace plumage::photonic_crystal
