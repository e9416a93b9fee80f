// The paper's accuracy comparison (§6.1, Figs. 8–9) as a library: several scattering-solver
// methods (plug-in type + options, optionally on the reduced layer geometry or with another local
// reflection) run on the same barbule segment at the same wavelengths and incident directions,
// each compared with the reference method (comparison_report.hpp). `plumage compare` is a shell
// over these calls: load_comparison → select_in_comparison → prepare_comparison →
// make_comparison_segment → run_comparison → compare_methods → write_comparison_tables /
// draw_comparison_figures. Schema of the config: docs/formats.md ("Comparison configs").
//
// Methods are created through the registry; nothing here names a plug-in.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "plumage/cross_section.hpp"
#include "plumage/far_field.hpp"
#include "plumage/local_reflection.hpp"
#include "plumage/plugin_registry.hpp"
#include "plumage/reduced_regions.hpp"
#include "plumage/scattering_solver.hpp"
#include "plumage/species_config.hpp"
#include "plumage/structure_generator.hpp"

namespace plumage {

struct ComparisonMethod {
  enum class Geometry { exact, reduced_layers };
  std::string name;
  std::string solver_type;
  // The solver section as flow YAML with double-quoted scalars (the type's name alone when the
  // method names only a type), recorded in the times CSV.
  std::string solver_options;
  Geometry geometry = Geometry::exact;
  std::shared_ptr<const ScatteringSolver> solver;
  std::shared_ptr<const LocalReflection> reflection;
  std::string reflection_note;  // "species" or the override's model
  SourceMark geometry_mark;     // where `geometry` is (for the error of a missing layered model)
  std::string geometry_field;
};

// "exact" or "reduced_layers".
const char* geometry_name(ComparisonMethod::Geometry geometry);

struct Comparison {
  std::filesystem::path file;
  std::string name;
  SpeciesConfig species;
  // The species' generator with its outline width set to segment_um (and structure_overrides
  // applied): a ConfigDocument::derive of the species' structure section.
  std::shared_ptr<const StructureGenerator> generator;
  double segment_um = 10.0;
  std::uint64_t instance = 0;
  std::vector<double> lambdas;               // nm, strictly increasing
  std::vector<IncidentDirection> incidents;  // radians
  int pattern_samples = 400;
  std::vector<ComparisonMethod> methods;
  std::size_t reference = 0;  // index into methods
  ReducedRegionOptions reduced;
};

// Loads and validates a comparison config, creating every method's solver (nothing runs).
// Throws ConfigError naming file, line and field.
Comparison load_comparison(const std::filesystem::path& file, const PluginRegistry& registry);

// What a comparison holds, in one line ("comparison tiny, 4 methods (reference reflected), ...").
std::string describe_comparison(const Comparison& comparison);
// load_comparison then describe_comparison: what `plumage check` says of a comparison config.
std::string check_comparison_config(const std::filesystem::path& file, const PluginRegistry& registry);

// A part of a comparison to run. Each field left empty keeps the config's choice. A name or
// wavelength the comparison does not have is a ConfigError located at the command-line flag
// that sets the field (--only, --reference, --wavelengths, --instance).
struct ComparisonSelection {
  std::vector<std::string> only;   // run only these methods (the reference always runs)
  std::string reference;           // compare against this method instead
  std::vector<double> wavelengths_nm;  // run only these of the config's wavelengths
  std::optional<std::int64_t> instance;  // another barbule instance (>= 0)
};
void select_in_comparison(Comparison& comparison, const ComparisonSelection& selection);

// The explicit preparation step (local_reflection.hpp) for every local reflection a method uses.
void prepare_comparison(const Comparison& comparison, const PreparationOptions& options);

// The barbule segment of the comparison's instance, exact and (when a method asks for it)
// reduced. Throws Error for an invalid section, ConfigError at the method's `geometry` when it
// asks for reduced layers of a barbule without a layered model.
struct ComparisonSegment {
  CrossSection exact;
  std::optional<CrossSection> reduced;
};
ComparisonSegment make_comparison_segment(const Comparison& comparison);

// One method's far fields and wall times.
struct MethodRun {
  std::vector<std::vector<FarField>> results;  // [incident][wavelength]
  double prepare_s = 0.0;                      // instance-only work (meshing...)
  double solve_s = 0.0;                        // every wavelength and incident direction
  std::vector<double> solve_s_per_lambda;
  std::size_t regions = 0;
};

// Called after every solve (one method, one wavelength, one θ_i): solves done, total, and the
// estimated remaining seconds (each method priced at its own mean so far; see run_comparison).
using ComparisonProgress = std::function<void(std::size_t done, std::size_t total, double remaining_s)>;

// Refuses (MemoryBudgetError, exit status 2) a comparison any of whose methods would not fit at
// any of its wavelengths (ScatteringSolver::estimate_memory); run_comparison calls it first, so
// a BEM method over the budget stops the run before the first method starts.
void check_comparison_memory(const Comparison& comparison, const ComparisonSegment& segment);
// Solves run_comparison makes: methods × wavelengths × distinct θ_i.
std::size_t comparison_solve_count(const Comparison& comparison);

// Runs every method on the segment, method after method; incident directions that share θ_i
// are one solve. Returns one MethodRun per method, in the comparison's order. The methods'
// reflections must be prepared (prepare_comparison).
std::vector<MethodRun> run_comparison(const Comparison& comparison, const ComparisonSegment& segment,
                                      const ComparisonProgress& progress = {});

}  // namespace plumage
