#pragma once
// Entry points of the `seam` executable: a whole run, or a check of the input.
#include <string>
#include <vector>

namespace seam::app {

struct RunOptions {
  std::string input;
  std::string output_dir; ///< empty: "<input stem>_out" in the working directory
  bool quiet = false;
  std::string restart; ///< checkpoint to continue from; empty: start at t = 0
  std::vector<std::string> petsc_args;
};

const char* version();

/// `seam run`: returns the exit code (0); throws InputError / SolverError / others.
int run(const RunOptions& options, int argc, char** argv);

/// `seam check`: parse, validate, load the mesh, print a summary; returns the exit code.
int check(const std::string& input, const std::vector<std::string>& petsc_args);

} // namespace seam::app
