#pragma once
// What a fluid or fluid-structure run needs to write checkpoints and restart from one
// (checkpoint.hpp).
#include <string>

namespace seam::problem {

/// The input file (its hash identifies checkpoints) and the checkpoint to restart from
/// (empty: start at t = 0).
struct RestartFrom {
  std::string input;
  std::string checkpoint;
};

} // namespace seam::problem
