#pragma once
// seam-bench subcommands: each benchmark file registers one with a static Register object,
//   static const seam::bench::Register reg{"name", "one-line summary", &run_function};
// and main.cpp dispatches `seam-bench name ...` to it.
#include <string>
#include <vector>

namespace seam::bench {

/// A subcommand receives its own arguments (argv[0] is the subcommand name); returns the exit
/// code.
using Run = int (*)(int argc, char** argv);

struct Command {
  std::string name;
  std::string summary;
  Run run;
};

inline std::vector<Command>& commands() {
  static std::vector<Command> all;
  return all;
}

struct Register {
  Register(std::string name, std::string summary, Run run) {
    commands().push_back({std::move(name), std::move(summary), run});
  }
};

} // namespace seam::bench
