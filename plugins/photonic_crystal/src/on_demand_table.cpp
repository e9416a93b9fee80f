#include "on_demand_table.hpp"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "plumage/atomic_file.hpp"
#include "plumage/config_document.hpp"
#include "plumage/error.hpp"
#include "plumage/plugin_registry.hpp"

namespace plumage::photonic_crystal {

namespace fs = std::filesystem;

namespace {

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

std::size_t grid_entries(const TableGrid& g) { return g.lambda_nm.size() * g.cos_theta.size() * g.cos_phi.size(); }

}  // namespace

OnDemandTable::OnDemandTable(const OnDemandRequest& r, const PluginContext& context)
    : cell_(load_crystal_cell(r.crystal_file)), crystal_file_(r.crystal_file.string()), builder_type_(r.builder_type) {
  config_hash_ = fnv1a_hex(read_bytes(r.crystal_file));
  const auto [lo, hi] = r.lambda_nm;
  std::ostringstream key;
  key << "crystal=" << config_hash_ << ";builder=" << builder_type_ << ";";
  if (r.builder_params) flatten(*r.builder_params, key);
  key << ";grid=" << lo << "," << hi << "," << r.n_lambda << "," << r.n_theta << "," << r.n_phi;
  const fs::path cache = context.cache_dir.empty() ? fs::path("build/cache") : context.cache_dir;
  const std::string stem = r.crystal_file.stem().string();
  file_ = (cache / "tables" / (stem + "-" + fnv1a_hex(key.str()) + ".plt")).string();
  grid_ = TableGrid::uniform(lo, hi, r.n_lambda, r.n_theta, r.n_phi);
  // The preview stand-in: the builder's preview fidelity on 4 λ × 5 cos θ × 5 cos φ over the same
  // λ range, cached under its own key.
  std::ostringstream pkey;
  pkey << "crystal=" << config_hash_ << ";builder=" << builder_type_ << ";fidelity{preview};grid=" << lo << "," << hi
       << ",4,5,5";
  preview_file_ = (cache / "tables" / (stem + "-preview-" + fnv1a_hex(pkey.str()) + ".plt")).string();
  preview_grid_ = TableGrid::uniform(lo, hi, 4, 5, 5);
  // A cached table needs no builder (an installation may lack the builder's plug-in); otherwise
  // the builders are created now, so that their parameters are checked when the species loads.
  if (!context.registry) return;
  if (!context.registry->find(TableBuilder::plugin_kind, builder_type_) && fs::exists(file_)) return;
  builder_ = context.registry->create_named<TableBuilder>(builder_type_, r.builder_params ? *r.builder_params : ParamView{},
                                                          context);
  const ConfigDocument preview_doc = ConfigDocument::parse("fidelity: preview\n", "the preview table's builder");
  preview_builder_ = context.registry->create_named<TableBuilder>(builder_type_, preview_doc.root(), context);
}

std::string OnDemandTable::describe(bool preview) const {
  const TableGrid& g = preview ? preview_grid_ : grid_;
  std::ostringstream os;
  os << cell_.name << " (" << g.lambda_nm.size() << " x " << g.cos_theta.size() << " x " << g.cos_phi.size()
     << " entries)";
  return os.str();
}

std::size_t OnDemandTable::entries(bool preview) const { return grid_entries(preview ? preview_grid_ : grid_); }

bool OnDemandTable::preview_replaces() const { return grid_entries(grid_) > grid_entries(preview_grid_); }

const TableBuilder& OnDemandTable::builder(bool preview) const {
  const auto& b = preview ? preview_builder_ : builder_;
  if (!b) {
    throw Error("photonic_crystal: building " + file(preview) + " needs the table_builder plug-in '" + builder_type_ +
                "'");
  }
  return *b;
}

ReflectionTable OnDemandTable::build(bool preview, const TableBuilder::Progress& progress) const {
  const TableGrid& grid = preview ? preview_grid_ : grid_;
  ReflectionTable t = builder(preview).build(cell_, grid, progress);
  t.metadata().config_hash = config_hash_;
  const fs::path out(file(preview));
  create_output_directory(out.parent_path());
  t.save(out);  // atomic (ReflectionTable::save)
  return t;
}

}  // namespace plumage::photonic_crystal
