// The reflection table of a `crystal:` reflection (crystal_table_reflection.hpp): what to build
// (the crystal cell, the table_builder and its parameters, the grid) and where it is cached,
// <cache>/tables/<crystal>-<key>.plt with the key a hash of the crystal file's bytes, the builder,
// its parameters and the grid; and the 4 λ × 5 cos θ × 5 cos φ preview table that
// PreparationOptions::Tables::preview puts in its place, cached under its own key.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "plumage/crystal_cell.hpp"
#include "plumage/local_reflection.hpp"
#include "plumage/params.hpp"
#include "plumage/plugin.hpp"
#include "plumage/reflection_table.hpp"
#include "plumage/table_builder.hpp"

namespace plumage::photonic_crystal {

// What the `crystal:` form of the reflection section asks for (crystal_table_reflection.cpp).
struct OnDemandRequest {
  std::filesystem::path crystal_file;
  std::string builder_type = "fdtd_periodic";
  std::optional<ParamView> builder_params;  // the `builder:` map, handed to the builder's factory
  std::pair<double, double> lambda_nm{400.0, 700.0};
  int n_lambda = 50, n_theta = 20, n_phi = 50;
};

class OnDemandTable {
 public:
  // Validates the crystal now (file:line:col errors) and creates the builders, so a bad builder
  // parameter is reported when the species loads; builds nothing.
  OnDemandTable(const OnDemandRequest& request, const PluginContext& context);

  // "mallard-green (50 x 20 x 50 entries)".
  std::string describe(bool preview) const;
  std::size_t entries(bool preview) const;
  // The file of the configured table, or of its preview stand-in.
  const std::string& file(bool preview) const { return preview ? preview_file_ : file_; }
  // Whether the preview option replaces this table: only tables larger than the preview grid
  // (smaller ones are built as asked).
  bool preview_replaces() const;
  // Builds the table (or its preview) with the builder, reporting progress, and saves it to its
  // cache file (atomically).
  ReflectionTable build(bool preview, const TableBuilder::Progress& progress) const;

 private:
  const TableBuilder& builder(bool preview) const;

  CrystalCell cell_;
  std::string crystal_file_, config_hash_, builder_type_;
  TableGrid grid_, preview_grid_;
  std::string file_, preview_file_;
  std::unique_ptr<TableBuilder> builder_, preview_builder_;
};

}  // namespace plumage::photonic_crystal
