// local_reflection "photonic_crystal": Jones reflection of a photonic-crystal half-space from a
// ReflectionTable (issue 5; spec wave-simulation.md §3). Parameter table: crystal_table_reflection.cpp.
// Per-node regularity is applied by the solver, not here.
//
// With `crystal:` the table is looked up in the cache when the model is created and, if missing,
// built on the first reflect() (so loading a species config never runs the FDTD). The environment
// variable PLUMAGE_TABLE_BUILD controls that build: unset or "build" (default) builds as
// configured; "preview" builds a small preview-fidelity table (4 λ × 5 × 5) instead of any larger
// one (cached under its own key, for tests and quick looks); "never" refuses with a message naming the missing table. When the
// variable is unset and the process runs under CTest (CTEST_INTERACTIVE_DEBUG_MODE is set), the
// default is "preview", so the default test suite never starts a production build.
#pragma once

#include <filesystem>
#include <memory>
#include <mutex>
#include <string>

#include "plumage/crystal_cell.hpp"
#include "plumage/table_builder.hpp"

#include "plumage/local_reflection.hpp"
#include "plumage/reflection_table.hpp"

namespace plumage::photonic_crystal {

class CrystalTableReflection final : public LocalReflection {
 public:
  CrystalTableReflection(const ParamView& params, const PluginContext& context);
  void reflect(std::span<const Request> requests, std::span<JonesReflection> out) const override;
  static std::vector<ParamSpec> param_table();

  // The table (built or loaded on first use).
  const ReflectionTable& table() const;
  const std::string& table_file() const { return table_file_; }

 private:
  void build_or_load() const;

  mutable ReflectionTable table_;
  mutable std::once_flag ready_;
  std::string table_file_;
  // On-demand build (crystal:): everything needed later, validated at construction.
  std::unique_ptr<TableBuilder> builder_, preview_builder_;
  CrystalCell cell_;
  std::string crystal_file_, config_hash_, preview_file_;
  TableGrid grid_;
};

}  // namespace plumage::photonic_crystal
