// fit_structure (plumage/structure_fit.hpp): bounded Levenberg–Marquardt (Ceres) from several
// deterministic starts, central differences kept inside the bounds, and the linearised covariance
// s²(JᵀJ)⁻¹ (ceres::Covariance, dense SVD) at the best start.
#include <ceres/ceres.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <limits>

#include "plumage/structure_fit.hpp"

namespace plumage {

namespace {

// Radical inverse of `index` in `base`: the Halton sequence (Halton 1960), one prime per parameter.
double radical_inverse(std::uint64_t index, std::uint64_t base) {
  double inverse = 1.0 / static_cast<double>(base), f = inverse, out = 0.0;
  while (index > 0) {
    out += f * static_cast<double>(index % base);
    index /= base;
    f *= inverse;
  }
  return out;
}

constexpr std::uint64_t kPrimes[] = {2, 3, 5, 7, 11, 13, 17, 19, 23, 29, 31, 37, 41, 43, 47, 53};

// Start k: the spec's own (k = 0), else Halton point seed + k mapped into the box.
std::vector<double> start_point(const FitSpec& spec, std::size_t k) {
  std::vector<double> x;
  for (std::size_t j = 0; j < spec.parameters.size(); ++j) {
    const FitParameter& p = spec.parameters[j];
    if (k == 0) {
      x.push_back(p.start.value_or(p.file_value));
    } else {
      x.push_back(p.lower + (p.upper - p.lower) * radical_inverse(spec.seed + k, kPrimes[j % std::size(kPrimes)]));
    }
  }
  return x;
}

// Weighted residuals (R_model − R)/σ with central differences: each parameter is stepped by
// h = relative_step · max(|x|, 1e-3 (upper − lower)) both ways, each side clipped to the bounds
// (the model may not exist outside them: a negative thickness, overlapping rods), so that a
// parameter at a bound gets the one-sided difference.
class DifferencedResiduals final : public ceres::CostFunction {
 public:
  DifferencedResiduals(const FitSpec& spec, const StructureForwardModel& model, std::size_t& evaluations)
      : spec_(spec), model_(model), evaluations_(evaluations) {
    set_num_residuals(static_cast<int>(spec.targets.size()));
    mutable_parameter_block_sizes()->push_back(static_cast<int>(spec.parameters.size()));
  }

  // The residuals at x; false when the model fails there (Ceres then rejects the step).
  bool residuals(const std::vector<double>& x, double* r) const {
    std::vector<double> predicted;
    try {
      ++evaluations_;
      predicted = model_.predict(x);
    } catch (const ConfigError& e) {
      last_error_ = e.what();  // a value the file does not admit (rods overlapping, ...)
      return false;
    }
    for (std::size_t i = 0; i < spec_.targets.size(); ++i) {
      r[i] = (predicted[i] - fit_target_value(spec_.targets[i])) / spec_.targets[i].sigma;
      if (!std::isfinite(r[i])) throw NumericalError("fit: the forward model returned a non-finite reflectance");
    }
    return true;
  }

  bool Evaluate(double const* const* parameters, double* r, double** jacobians) const override {
    const std::size_t n = spec_.parameters.size(), m = spec_.targets.size();
    std::vector<double> x(parameters[0], parameters[0] + n);
    if (!residuals(x, r)) return false;
    if (!jacobians || !jacobians[0]) return true;
    std::vector<double> plus(m), minus(m);
    for (std::size_t j = 0; j < n; ++j) {
      const FitParameter& p = spec_.parameters[j];
      const double h = spec_.relative_step * std::max(std::abs(x[j]), 1e-3 * (p.upper - p.lower));
      std::vector<double> xp = x, xm = x;
      xp[j] = std::min(x[j] + h, p.upper);
      xm[j] = std::max(x[j] - h, p.lower);
      if (!residuals(xp, plus.data())) xp[j] = x[j], std::copy(r, r + m, plus.begin());
      if (!residuals(xm, minus.data())) xm[j] = x[j], std::copy(r, r + m, minus.begin());
      if (xp[j] == xm[j]) return false;
      for (std::size_t i = 0; i < m; ++i) jacobians[0][i * n + j] = (plus[i] - minus[i]) / (xp[j] - xm[j]);
    }
    return true;
  }

  const std::string& last_error() const { return last_error_; }

 private:
  const FitSpec& spec_;
  const StructureForwardModel& model_;
  std::size_t& evaluations_;
  mutable std::string last_error_;
};

struct Solved {
  FitStart start;
  std::unique_ptr<ceres::Problem> problem;
  std::vector<double> x;
};

Solved solve_from(const FitSpec& spec, const StructureForwardModel& model, std::vector<double> x0,
                  std::size_t& evaluations) {
  Solved s;
  s.start.start = x0;
  s.x = std::move(x0);
  auto* cost = new DifferencedResiduals(spec, model, evaluations);
  std::vector<double> r0(spec.targets.size());
  if (!cost->residuals(s.x, r0.data())) {
    const std::string why = cost->last_error();
    delete cost;
    throw Error(spec.file.string() + ": the model cannot be evaluated at a start: " + why);
  }
  s.problem = std::make_unique<ceres::Problem>();
  s.problem->AddResidualBlock(cost, nullptr, s.x.data());
  for (std::size_t j = 0; j < spec.parameters.size(); ++j) {
    s.problem->SetParameterLowerBound(s.x.data(), static_cast<int>(j), spec.parameters[j].lower);
    s.problem->SetParameterUpperBound(s.x.data(), static_cast<int>(j), spec.parameters[j].upper);
  }
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = spec.max_iterations;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  // Ceres' defaults (cost change 1e-6 relative, step 1e-8 relative): far below 1σ of any fit with
  // noise, and a model with numerical noise of its own (FDTD) does not iterate on that noise.
  ceres::Solver::Summary summary;
  ceres::Solve(options, s.problem.get(), &summary);
  s.start.value = s.x;
  s.start.chi2 = 2.0 * summary.final_cost;  // Ceres' cost is ½ Σ r²
  s.start.iterations = static_cast<int>(summary.iterations.size());
  s.start.converged = summary.termination_type == ceres::CONVERGENCE;
  s.start.message = summary.message;
  return s;
}

// σ and correlations of the best start: C = s² (JᵀJ)⁻¹ with s² = χ²/(m − n).
void covariance_of(const FitSpec& spec, Solved& best, FitResult& out) {
  const std::size_t n = spec.parameters.size();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  out.sigma.assign(n, nan);
  out.correlation.assign(n * n, nan);
  ceres::Covariance::Options options;
  options.algorithm_type = ceres::DENSE_SVD;
  options.num_threads = 1;
  ceres::Covariance covariance(options);
  const std::vector<std::pair<const double*, const double*>> blocks{{best.x.data(), best.x.data()}};
  std::vector<double> c(n * n);
  if (!covariance.Compute(blocks, best.problem.get()) || !covariance.GetCovarianceBlock(best.x.data(), best.x.data(), c.data())) {
    out.covariance_note = "JᵀJ is singular: a parameter does not change the prediction, or two change it alike";
    return;
  }
  for (std::size_t j = 0; j < n; ++j) {
    if (!std::isfinite(c[j * n + j]) || c[j * n + j] <= 0.0) {
      out.covariance_note = "JᵀJ is singular at the best values: " + spec.parameters[j].path + " has no finite variance";
      return;
    }
  }
  // Exactly determined (m = n): no residual estimates the noise, so σ takes the targets' stated σ
  // as they are (s² = 1), i.e. how far each parameter moves when a target moves by its σ.
  const bool determined = out.residuals == n;
  if (determined) out.covariance_note = "as many targets as parameters: σ from the targets' stated σ (s² = 1)";
  for (std::size_t j = 0; j < n; ++j) out.sigma[j] = std::sqrt((determined ? 1.0 : out.reduced_chi2) * c[j * n + j]);
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t k = 0; k < n; ++k) out.correlation[j * n + k] = c[j * n + k] / std::sqrt(c[j * n + j] * c[k * n + k]);
}

// Every parameter must change the prediction at the first start (else the fit cannot determine it:
// e.g. the base nominal_stack of a species whose variant has its own). ConfigError at the spec.
void check_sensitivity(const FitSpec& spec, const StructureForwardModel& model, std::size_t& evaluations) {
  const std::size_t n = spec.parameters.size(), m = spec.targets.size();
  DifferencedResiduals cost(spec, model, evaluations);
  std::vector<double> x = start_point(spec, 0), r(m), jacobian(m * n);
  const double* parameters[] = {x.data()};
  double* jacobians[] = {jacobian.data()};
  if (!cost.Evaluate(parameters, r.data(), jacobians))
    throw Error(spec.file.string() + ": the model cannot be evaluated at or beside the first start: " + cost.last_error());
  for (std::size_t j = 0; j < n; ++j) {
    bool changes = false;
    for (std::size_t i = 0; i < m; ++i) changes = changes || jacobian[i * n + j] != 0.0;
    if (!changes)
      throw ConfigError(spec.parameters[j].mark, spec.parameters[j].field,
                        "'" + spec.parameters[j].path + "' does not change the prediction (is it replaced by the variant, "
                        "or not used by the model?)");
  }
}

}  // namespace

FitResult fit_structure(const FitSpec& spec, const StructureForwardModel& model,
                        const std::function<void(std::size_t done, std::size_t total)>& progress) {
  const std::clock_t cpu0 = std::clock();
  const auto wall0 = std::chrono::steady_clock::now();
  FitResult out;
  std::vector<Solved> solved;
  check_sensitivity(spec, model, out.evaluations);
  for (std::size_t k = 0; k < static_cast<std::size_t>(spec.starts); ++k) {
    solved.push_back(solve_from(spec, model, start_point(spec, k), out.evaluations));
    out.starts.push_back(solved.back().start);
    if (progress) progress(k + 1, static_cast<std::size_t>(spec.starts));
  }
  for (std::size_t k = 1; k < solved.size(); ++k)
    if (solved[k].start.chi2 < solved[out.best].start.chi2) out.best = k;
  Solved& best = solved[out.best];
  const std::size_t n = spec.parameters.size();
  out.value = best.x;
  out.chi2 = best.start.chi2;
  out.residuals = spec.targets.size();
  out.reduced_chi2 = out.residuals > n ? out.chi2 / static_cast<double>(out.residuals - n)
                                       : std::numeric_limits<double>::quiet_NaN();
  out.at_bound.resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    const FitParameter& p = spec.parameters[j];
    const double tol = 1e-6 * (p.upper - p.lower);
    out.at_bound[j] = out.value[j] <= p.lower + tol || out.value[j] >= p.upper - tol;
  }
  covariance_of(spec, best, out);
  out.prediction = model.predict(out.value);
  ++out.evaluations;
  out.cpu_seconds = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
  out.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return out;
}

}  // namespace plumage
