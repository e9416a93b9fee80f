// AccuracyLadder "multilayer": periodic stacks of growing period count against their closed form.
#pragma once

#include "plumage/accuracy_ladder.hpp"

namespace plumage::multilayer {

class MultilayerLadder final : public AccuracyLadder {
 public:
  std::vector<LadderPoint> run(const Options& options) const override;
};

}  // namespace plumage::multilayer
