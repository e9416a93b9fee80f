// The rcwa plug-in's accuracy ladder (issue 27): the solver at growing (harmonics, slices) on a
// crystal against its finest rung.
#pragma once

#include <string>
#include <vector>

#include "plumage/accuracy_ladder.hpp"
#include "plumage/param_table.hpp"

namespace plumage::rcwa {

struct LadderParams {
  std::string crystal;
};
const ParamTable<LadderParams>& ladder_params();

std::vector<LadderPoint> run_rcwa_ladder(const AccuracyLadder::Options& options, const std::string& crystal_file);

}  // namespace plumage::rcwa
