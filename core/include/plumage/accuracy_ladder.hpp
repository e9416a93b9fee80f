// Extension point: a backend's accuracy ladder (issue 9). Each backend runs itself at a ladder of
// fidelity settings against an independent reference of its own choosing (an analytic solution,
// a different method, its finest setting) and reports the error and the cost of every rung.
// `plumage bench ladder` runs every registered ladder and charts error against wall time, so a
// third-party backend shows up on the same chart by registering one of these beside itself.
//
// Implementations: "multilayer" (closed-form periodic stacks), "bem" (exact cylinder series),
// "pathtracer" (converged render), and core's own for the approximate solver and the fitter.
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "plumage/plugin.hpp"

namespace plumage {

// One rung: a backend at one setting, against one reference.
struct LadderPoint {
  std::string backend;    // "bem", "multilayer", ...: one curve per (backend, case) on the chart
  std::string case_name;  // what was computed, e.g. "keratin cylinder r=250nm, 550nm"
  std::string setting;    // the rung, e.g. "ppw=16"
  double fidelity = 0.0;  // the rung's numeric knob (ppw, spp, periods, ...), for ordering
  std::string reference;  // e.g. "exact cylinder series (plugins/bem/reference)"
  std::string metric;     // e.g. "rel. L2 of |E|^2 over 360 directions"
  double error = 0.0;     // against the reference, in `metric`
  double wall_s = 0.0;    // of this rung alone (the reference's cost excluded)
  double cpu_s = 0.0;     // process CPU time of the rung (all threads)
};

class AccuracyLadder : public PluginObject {
 public:
  static constexpr std::string_view plugin_kind = "accuracy_ladder";

  struct Options {
    bool quick = false;  // the CI variant: a few cheap rungs (seconds), not the full ladder
    std::function<void(std::string_view)> progress;  // one line per rung; may be empty
  };

  virtual std::vector<LadderPoint> run(const Options& options) const = 0;
};

// Wall and process-CPU seconds of a callable, for ladders.
struct RungCost {
  double wall_s = 0.0;
  double cpu_s = 0.0;
};
RungCost measure_rung(const std::function<void()>& work);

}  // namespace plumage
