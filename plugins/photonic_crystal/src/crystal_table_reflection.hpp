// local_reflection "photonic_crystal": Jones reflection of a photonic-crystal half-space from a
// ReflectionTable (issue 5; spec wave-simulation.md §3). Parameter table: crystal_table_reflection.cpp.
// Per-node regularity is applied by the solver, not here.
#pragma once

#include <memory>
#include <string>

#include "plumage/local_reflection.hpp"
#include "plumage/reflection_table.hpp"

namespace plumage::photonic_crystal {

class CrystalTableReflection final : public LocalReflection {
 public:
  CrystalTableReflection(const ParamView& params, const PluginContext& context);
  void reflect(std::span<const Request> requests, std::span<JonesReflection> out) const override;
  static std::vector<ParamSpec> param_table();

  const ReflectionTable& table() const { return table_; }
  const std::string& table_file() const { return table_file_; }

 private:
  ReflectionTable table_;
  std::string table_file_;
};

}  // namespace plumage::photonic_crystal
