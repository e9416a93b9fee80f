// local_reflection "photonic_crystal": Jones reflection of a photonic-crystal half-space from a
// ReflectionTable (issue 5; spec wave-simulation.md §3). Parameter table: crystal_table_reflection.cpp.
// Per-node regularity is applied by the solver, not here.
//
// `table:` names a table file, loaded when the model is created. `crystal:` names a crystal
// config whose table is built by a table_builder plug-in and cached by content hash
// (on_demand_table.hpp). Creating the model never builds or loads that table: the explicit
// preparation step does (prepare(), called by prepare_species before any simulation; issue 22),
// and reflect() before it throws. PreparationOptions::Tables says how: build (load the cached
// table or build it, ~10–15 min for a production-size table), preview (the 4 λ × 5 × 5 preview
// table instead of a larger one — a test shortcut, raised as the warning
// photonic_crystal.preview_table so every file made with it says so) or never (load the cached
// table or refuse, naming it).
//
// prepare() raises the warnings the table's builder wrote into its notes ("WARNING: … [code]")
// on every call, so a run that prepares the model, and every file it writes, carries them.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "on_demand_table.hpp"
#include "plumage/local_reflection.hpp"
#include "plumage/reflection_table.hpp"

namespace plumage::photonic_crystal {

class CrystalTableReflection final : public LocalReflection {
 public:
  CrystalTableReflection(const ParamView& params, const PluginContext& context);

  std::string pending_preparation() const override;
  void prepare(const PreparationOptions& options) const override;
  void reflect(std::span<const Request> requests, std::span<JonesReflection> out) const override;

  // The parameters, declared once (crystal_table_reflection.cpp).
  static std::vector<ParamSpec> param_table();

  // The table in use; throws when it is not prepared.
  const ReflectionTable& table() const;

 private:
  void make_ready(const PreparationOptions& options) const;
  [[noreturn]] void refuse(const std::string& why) const;

  std::unique_ptr<OnDemandTable> on_demand_;  // null for `table:`
  mutable std::mutex mutex_;
  mutable std::atomic<bool> ready_{false};
  mutable ReflectionTable table_;
  mutable std::string table_file_;  // the file table_ came from
  mutable bool preview_ = false;    // table_ is the preview stand-in
  mutable bool raised_on_build_ = false;  // its builder has just raised the table's warnings
  mutable std::vector<std::pair<std::string, std::string>> table_warnings_;  // (code, message)
};

}  // namespace plumage::photonic_crystal
