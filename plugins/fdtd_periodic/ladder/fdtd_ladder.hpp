// The plug-in's accuracy ladder (issue 9): the engine at growing resolution against the
// closed-form Airy recursion of a layered stack and against its finest rung on a crystal.
#pragma once

#include <string>
#include <vector>

#include "plumage/accuracy_ladder.hpp"
#include "plumage/param_table.hpp"

namespace plumage::fdtd_table {

struct LadderParams {
  std::string crystal;  // the crystal of the second case
};
const ParamTable<LadderParams>& ladder_params();

std::vector<LadderPoint> run_fdtd_ladder(const AccuracyLadder::Options& options, const std::string& crystal_file);

}  // namespace plumage::fdtd_table
