// seam command line: `seam run INPUT.yaml`, `seam check INPUT.yaml`, `seam --help | --version`.
// Exit codes (CONTRACT.md): 0 success, 1 bad input, 2 solver gave up, 3 internal error.
#include "seam/app/run.hpp"
#include "seam/common/error.hpp"

#include <CLI/CLI.hpp>
#include <mpi.h>

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

namespace {

int rank_of_world() {
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}

void report(const char* kind, const std::exception& e) {
  if (rank_of_world() == 0) std::fprintf(stderr, "seam: %s%s\n", kind, e.what());
}

int dispatch(int argc, char** argv) {
  // Everything after `--` belongs to PETSc.
  std::vector<std::string> petsc_args;
  int n_own = argc;
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]) == "--") {
      n_own = i;
      for (int j = i + 1; j < argc; ++j) petsc_args.emplace_back(argv[j]);
      break;
    }

  CLI::App app{"seam: mortar finite element methods for mesh tying and contact"};
  app.set_version_flag("--version", std::string("seam ") + seam::app::version());
  app.require_subcommand(1);
  seam::app::RunOptions run_opts;
  auto* run = app.add_subcommand("run", "solve the problem described by INPUT.yaml");
  run->add_option("input", run_opts.input, "input file (YAML)")->required();
  run->add_option("-o,--output", run_opts.output_dir, "output directory (default <stem>_out)");
  run->add_flag("-q,--quiet", run_opts.quiet, "no per-step progress on the terminal");
  run->add_option("--restart", run_opts.restart,
                  "continue from a checkpoint directory (DIR/checkpoint_NNNNN)");
  std::string check_input;
  auto* check =
      app.add_subcommand("check", "parse and validate INPUT.yaml, load the mesh, solve nothing");
  check->add_option("input", check_input, "input file (YAML)")->required();

  try {
    app.parse(n_own, argv);
  } catch (const CLI::ParseError& e) {
    if (rank_of_world() == 0) app.exit(e);
    return e.get_exit_code() == 0 ? 0 : 1;
  }

  run_opts.petsc_args = petsc_args;
  if (*check) return seam::app::check(check_input, petsc_args);
  return seam::app::run(run_opts, argc, argv);
}

} // namespace

int main(int argc, char** argv) {
  // PT-Scotch 7, which partitions meshes read in chunks, runs threads that call MPI.
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_MULTIPLE, &provided);
  int code = 0;
  try {
    code = dispatch(argc, argv);
  } catch (const seam::InputError& e) {
    report("input error: ", e);
    code = 1;
  } catch (const seam::SolverError& e) {
    report("solver failed: ", e);
    code = 2;
  } catch (const std::exception& e) {
    report("internal error: ", e);
    code = 3;
  }
  MPI_Finalize();
  return code;
}
