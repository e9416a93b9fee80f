// Fitting nanostructure to a measured spectrum (issue 25, part 3): the inverse of `plumage spectra`.
//
// The parameters are numbers of a species or crystal file named by their YAML paths
// (`variants.forest.nominal_stack.layers.0.thickness_nm`, `crystal.rod_diameter_nm`; a number in a
// path indexes a list), each with bounds. A forward model predicts the specular reflectance R(λ, θ)
// of the file with those values replaced (ConfigDocument::derive), and the fit minimises the
// weighted sum of squares
//   χ²(p) = Σ_i ((R_model(λ_i, θ_i; p) − R_i) / σ_i)²
// within the bounds (Ceres, Levenberg–Marquardt, central numerical differences), from several
// deterministic starts (the spec's start, then a Halton sequence over the box). The 1σ
// uncertainty is the usual linearised one (e.g. Press et al., Numerical Recipes §15.6):
//   C = s² (JᵀJ)⁻¹,  s² = χ²_min / (m − n)   (m residuals, n parameters),
// which does not need σ to be known: with the right σ, s² ≈ 1; with σ = 1 (unweighted) it is the
// residual variance. It assumes the model is linear within a few σ and the noise independent.
//
// Forward models (cost per evaluation measured and reported):
//   nominal_stack   the species' nominal_stack through its LocalReflection plug-in (the stack of
//                   `plumage spectra`; thin films and multilayers: microseconds–milliseconds);
//   crystal_table   the crystal cell through a TableBuilder plug-in (`fdtd_periodic`, or any other,
//                   e.g. `rcwa`) on the tiny grid of the targets' λ × cos θ × {cos φ = 1}: the
//                   specular Jones reflection of the cell in the plane of incidence across the rods.
//   barbule         the whole barbule through the species' solver (`plumage simulate`, paper §4):
//                   the instance-mean reflectance density (Eq. 10) integrated over the pattern
//                   directions φ_o ∈ (−90°, 90°), incidence in the cross-section plane at φ_i = θ
//                   (θ_i = 0: pol 1 is s, pol 2 is p). Seconds to minutes per evaluation.
//
// The fit spec (YAML, docs/formats.md "fit spec"; parameters in docs/parameters.md, "fit spec"):
//   model: nominal_stack            # | crystal_table | barbule
//   config: ../species/rockdove.yaml   # species (nominal_stack) or crystal file (crystal_table)
//   variant: forest                 # species variant (nominal_stack; default: the file's)
//   builder: {type: fdtd_periodic, fidelity: preview}   # crystal_table: the TableBuilder and its options
//   parameters:
//     - {path: variants.forest.nominal_stack.layers.0.thickness_nm, bounds: [450, 750], start: 520}
//   target: {measured: rockdove.csv, theta_deg: 0, sigma: 0.01}
//     # or  target: {points: [{lambda_nm: 500, theta_deg: 0, R: 0.12, polarization: s, sigma: 0.01}, ...]}
//     # and/or  peaks: [{lambda_nm: 507.5, theta_deg: 0, polarization: s, sigma_nm: 2.5, window_nm: 40}]
//
// A peak target fits the position of a reflectance maximum (a spectrometer's peak, or a design hue
// to keep while the brightness is fitted): the model is evaluated at λ_t + k·step over the window
// λ_t ± window/2 and the peak is the vertex of the least-squares parabola through those samples
// (smooth in the parameters, unlike an arg-max); its residual is (λ_peak − λ_t)/σ_nm.
//   starts: 4
//   seed: 1
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "plumage/error.hpp"
#include "plumage/params.hpp"
#include "plumage/plugin_registry.hpp"

namespace plumage {

enum class FitModel { nominal_stack, crystal_table, barbule };
enum class FitPolarization { unpolarized, s, p };

// One fitted number: a YAML path in the model's file and its bounds.
struct FitParameter {
  std::string path;
  double lower = 0.0, upper = 0.0;
  std::optional<double> start;  // default: the file's own value
  double file_value = 0.0;      // the value in the file (checked to be a number)
  SourceMark mark;              // the parameter's path in the spec (for messages)
  std::string field;            // its field there, "parameters[0].path"
};

enum class FitTargetKind { reflectance, peak };

// One value to fit: R at (λ, θ), or (kind peak) the wavelength of the reflectance maximum near
// λ at θ; its standard deviation σ (a fraction for R, nm for a peak) and polarization.
struct FitTarget {
  double lambda_nm = 0.0;  // peak: the target peak wavelength, also the window's centre
  double theta_deg = 0.0;
  double reflectance = 0.0;
  double sigma = 1.0;
  FitPolarization polarization = FitPolarization::unpolarized;
  FitTargetKind kind = FitTargetKind::reflectance;
  double window_nm = 0.0, step_nm = 0.0;  // peak: the sampled window and its step
};

// The target's value: R, or the peak wavelength in nm.
double fit_target_value(const FitTarget& t);

// The reflectances a forward model evaluates for the targets: each reflectance target itself, each
// peak target's window samples λ_t − window/2 … λ_t + window/2 (in that order).
std::vector<FitTarget> fit_model_samples(const std::vector<FitTarget>& targets);

// The targets' predictions from the samples' reflectances (same order as fit_model_samples): R, or
// the vertex of the least-squares parabola through a peak's window (parabola_peak_nm).
std::vector<double> fit_target_predictions(const std::vector<FitTarget>& targets, const std::vector<double>& sample_r);

// The wavelength of the maximum of the least-squares parabola R ≈ a + b·λ + c·λ² through
// (lambda_nm, r), clamped to one window width beyond the sampled range (a window on the peak's
// flank still points the fit the right way); a convex or flat fit gives the higher end.
double parabola_peak_nm(const std::vector<double>& lambda_nm, const std::vector<double>& r);

struct FitSpec {
  std::filesystem::path file;
  FitModel model = FitModel::nominal_stack;
  std::filesystem::path config;  // resolved against the spec's folder
  std::string variant;
  ParamView builder;               // crystal_table: {type: <table_builder>, <its own keys>...}
  std::vector<FitParameter> parameters;
  std::vector<FitTarget> targets;
  std::filesystem::path measured;  // the measured file, when the targets came from one
  int instances = 4;  // barbule: instances simulated per evaluation (0: the species' simulation.instances)
  int starts = 1;
  std::uint64_t seed = 1;
  int max_iterations = 50;
  // Central differences with step h = relative_step · max(|x|, 1e-3·(upper − lower)), one-sided
  // where a bound is nearer than h. A forward model that is noisy at small scale (an FDTD grid)
  // needs a step above its noise.
  double relative_step = 1e-4;
  std::string fitted_name;  // the new variant / crystal name (default: <variant>_fit, <name>-fit)
};

// Reads and validates a fit spec: the model's file is loaded, every parameter path must name a
// number in it, bounds low < high, a start inside them; the targets are read (a measured file
// through read_measured_spectrum with its angles resolved). Errors are ConfigError naming the
// spec's file:line:field (InputFileError for the measured file).
FitSpec load_fit_spec(const std::filesystem::path& file, const PluginRegistry& registry);

// A forward model: the targets' reflectances predicted for parameter values (in spec order).
class StructureForwardModel {
 public:
  virtual ~StructureForwardModel() = default;
  virtual std::vector<double> predict(const std::vector<double>& values) const = 0;
  virtual std::string description() const = 0;
};
std::unique_ptr<StructureForwardModel> make_forward_model(const FitSpec& spec, const PluginRegistry& registry);

// The file of the spec's model with the parameters set to `values`, as YAML (comments dropped):
// a species gets a new variant (spec.fitted_name) that copies the fitted variant with the values
// replaced and becomes the file's default (`variant:`); paths outside `variants.<variant>` are
// replaced in place. A crystal gets crystal.name = spec.fitted_name.
std::string fitted_config_yaml(const FitSpec& spec, const std::vector<double>& values);

struct FitStart {
  std::vector<double> start, value;
  double chi2 = 0.0;
  int iterations = 0;
  bool converged = false;
  std::string message;  // Ceres' termination message
};

struct FitResult {
  std::vector<double> value, sigma;   // best start's values and their 1σ (NaN when singular)
  std::vector<double> correlation;    // n×n, row-major (NaN when singular)
  std::vector<bool> at_bound;         // a value within 1e-6 of the range of a bound
  double chi2 = 0.0, reduced_chi2 = 0.0;
  std::size_t residuals = 0;
  std::vector<double> prediction;     // at the best values, per target
  std::vector<FitStart> starts;       // every start, in order
  std::size_t best = 0;
  std::size_t evaluations = 0;        // forward-model calls, all starts and the covariance
  double cpu_seconds = 0.0, wall_seconds = 0.0;
  std::string covariance_note;        // empty, or why σ is unavailable
};

// The multi-start bounded least-squares fit with its covariance. `progress` (may be empty) is
// called after each start. Throws NumericalError when the model returns non-finite values.
FitResult fit_structure(const FitSpec& spec, const StructureForwardModel& model,
                        const std::function<void(std::size_t done, std::size_t total)>& progress = {});

// The outputs of `plumage fit`: fit.txt, fit.csv (parameters, starts, spectrum), fit_peaks.csv
// (with peak targets), fit.png (with reflectance targets) and fitted.yaml in `out`, each written
// atomically. `draw` false skips the picture (no matplotlib). Returns the names written, in order.
std::vector<std::string> write_fit_outputs(const FitSpec& spec, const StructureForwardModel& model, const FitResult& result,
                       const std::filesystem::path& out, bool draw = true);
std::string fit_summary_text(const FitSpec& spec, const StructureForwardModel& model, const FitResult& result);

}  // namespace plumage
