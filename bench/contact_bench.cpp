// seam-bench contact: a contact run of seam split into its phases per Newton iteration
// (issue: Newton iterations per load step and time per iteration, split into search, mortar
// evaluation with linearization, bulk assembly and linear solve; the mortar share of an
// iteration should stay below the bulk assembly share, which is the baseline here).
//
//   seam-bench contact --input examples/hertz_3d/hertz_3d.yaml [--output DIR] [-- PETSc]
//
// It runs the input as `seam run --quiet` does, then reads the run's newton.csv (iterations
// per step) and summary.json (seconds per phase, maximum over ranks).
#include "registry.hpp"

#include "seam/problem/run.hpp"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p);
  if (!in) throw std::runtime_error("cannot read " + p.string());
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The number after "key": in a JSON text (first occurrence after `after`).
double json_number(const std::string& text, const std::string& key, const std::string& after) {
  const auto start = text.find("\"" + after + "\"");
  const auto at = text.find("\"" + key + "\"", start == std::string::npos ? 0 : start);
  if (at == std::string::npos) throw std::runtime_error("summary.json has no '" + key + "'");
  const auto colon = text.find(':', at);
  return std::strtod(text.c_str() + colon + 1, nullptr);
}

int run_contact_bench(int argc, char** argv) {
  seam::problem::RunOptions options;
  options.quiet = true;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument("missing value after " + a);
      return argv[++i];
    };
    if (a == "--input") {
      options.input = value();
    } else if (a == "--output") {
      options.output_dir = value();
    } else if (a == "--") {
      for (++i; i < argc; ++i) options.petsc_args.emplace_back(argv[i]);
    } else if (a == "--help" || a == "-h") {
      std::printf(
          "usage: seam-bench contact --input FILE.yaml [--output DIR] [-- PETSc options]\n");
      return 0;
    } else {
      throw std::invalid_argument("unknown option " + a);
    }
  }
  if (options.input.empty()) throw std::invalid_argument("--input FILE.yaml is required");
  if (options.output_dir.empty())
    options.output_dir = (std::filesystem::temp_directory_path() / "seam_contact_bench").string();
  seam::problem::run(options, argc, argv);

  // Iterations per step from newton.csv (the predictor row of a step is iteration 0).
  std::ifstream newton(std::filesystem::path(options.output_dir) / "newton.csv");
  std::string line;
  std::getline(newton, line);
  std::map<int, int> per_step;
  int corrections = 0;
  while (std::getline(newton, line)) {
    int step = 0, iteration = 0;
    if (std::sscanf(line.c_str(), "%d,%d", &step, &iteration) != 2) continue;
    per_step[step] = std::max(per_step[step], iteration);
  }
  for (const auto& [step, n] : per_step) corrections += n;
  const std::string summary = read_file(std::filesystem::path(options.output_dir) / "summary.json");
  const double wall = json_number(summary, "wall_seconds", "status");
  const char* phases[] = {"search", "mortar", "condensation", "assembly", "linear_solve", "output"};
  std::map<std::string, double> seconds;
  for (const char* p : phases) seconds[p] = json_number(summary, p, "timings");
  const int evaluations = corrections + static_cast<int>(per_step.size());
  std::printf("contact benchmark: %s\n", options.input.c_str());
  std::printf("  steps %zu, Newton corrections %d (%.2f per step), residual evaluations %d\n",
              per_step.size(), corrections,
              per_step.empty() ? 0.0 : double(corrections) / double(per_step.size()), evaluations);
  std::printf("  wall %.3f s, %.4f s per residual evaluation\n", wall, wall / evaluations);
  std::printf("  %-14s %10s %14s %10s\n", "phase", "seconds", "s/evaluation", "share");
  for (const char* p : phases)
    std::printf("  %-14s %10.3f %14.5f %9.1f%%\n", p, seconds[p], seconds[p] / evaluations,
                100.0 * seconds[p] / wall);
  const double mortar = seconds["search"] + seconds["mortar"];
  std::printf("  (search + mortar) / bulk assembly = %.3f\n",
              seconds["assembly"] > 0.0 ? mortar / seconds["assembly"] : 0.0);
  return 0;
}

const seam::bench::Register reg{
    "contact", "phases of a contact run per Newton iteration (--input FILE)", &run_contact_bench};

} // namespace
