#include "crystal_table_reflection.hpp"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "plumage/config_document.hpp"
#include "plumage/crystal_cell.hpp"
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

CrystalTableReflection::CrystalTableReflection(const ParamView& params, const PluginContext& context) {
  const bool has_table = params.has("table"), has_crystal = params.has("crystal");
  if (has_table == has_crystal)
    throw Error("photonic_crystal: give exactly one of table: (a .plt file) or crystal: (a crystal config)");
  if (has_table) {
    const fs::path file = resolve(context, params.text("table"));
    table_ = ReflectionTable::load(file);
    table_file_ = file.string();
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
  std::ostringstream key;
  key << "crystal=" << fnv1a_hex(read_bytes(crystal_file)) << ";builder=" << builder_type << ";";
  if (params.has("builder")) flatten(builder_params, key);
  key << ";grid=" << lo << "," << hi << "," << nl << "," << nt << "," << np;
  const fs::path cache = context.cache_dir.empty() ? fs::path("build/cache") : context.cache_dir;
  const fs::path file = cache / "tables" / (crystal_file.stem().string() + "-" + fnv1a_hex(key.str()) + ".plt");
  table_file_ = file.string();
  if (fs::exists(file)) {
    table_ = ReflectionTable::load(file);
    return;
  }
  if (!context.registry)
    throw Error("photonic_crystal: building " + file.string() + " needs the plug-in registry");
  const CrystalCell cell = load_crystal_cell(crystal_file);
  auto builder = context.registry->create_named<TableBuilder>(builder_type, builder_params, context);
  table_ = builder->build(cell, TableGrid::uniform(lo, hi, nl, nt, np), {});
  table_.metadata().config_hash = fnv1a_hex(read_bytes(crystal_file));
  fs::create_directories(file.parent_path());
  table_.save(file);
}

void CrystalTableReflection::reflect(std::span<const Request> requests, std::span<JonesReflection> out) const {
  if (out.size() < requests.size()) throw Error("photonic_crystal: output span shorter than requests");
  for (std::size_t i = 0; i < requests.size(); ++i)
    out[i] = table_.query(requests[i].lambda_nm, requests[i].incidence);
}

}  // namespace plumage::photonic_crystal
