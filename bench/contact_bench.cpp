// seam-bench contact: a contact run of seam split into its phases per Newton iteration
// (issue: Newton iterations per load step and time per iteration, split into search, mortar
// evaluation with linearization, bulk assembly and linear solve; the mortar share of an
// iteration should stay below the bulk assembly share, which is the baseline here).
//
//   seam-bench contact --input examples/hertz_3d/hertz_3d.yaml [--output DIR] [-- PETSc]
//   seam-bench contact --input examples/ironing/ironing_3d.yaml --compare-frictionless
//
// With --compare-frictionless the input is run a second time with the friction of every
// interface removed, and the cost of friction is printed: Newton corrections per load step,
// time per residual evaluation and per phase, and the share of the mortar and friction
// evaluation (search + mortar, which includes the frictional rows) in an iteration.
// It runs the input as `seam run --quiet` does, then reads the run's newton.csv (iterations
// per step) and summary.json (seconds per phase, maximum over ranks).
#include "registry.hpp"

#include "seam/app/run.hpp"

#include <mpi.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
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

/// Phases of one contact run, read from its newton.csv and summary.json.
struct Measurement {
  std::size_t steps = 0;
  int corrections = 0; ///< Newton corrections (the predictor row of a step is iteration 0)
  int evaluations = 0; ///< residual evaluations: corrections + one predictor per step
  double wall = 0.0;
  std::map<std::string, double> seconds;
};

const char* const phases[] = {"search",   "mortar",       "condensation",
                              "assembly", "linear_solve", "output"};

Measurement measure(const seam::app::RunOptions& options, int argc, char** argv) {
  seam::app::run(options, argc, argv);
  std::ifstream newton(std::filesystem::path(options.output_dir) / "newton.csv");
  std::string line;
  std::getline(newton, line);
  std::map<int, int> per_step;
  while (std::getline(newton, line)) {
    int step = 0, iteration = 0;
    if (std::sscanf(line.c_str(), "%d,%d", &step, &iteration) != 2) continue;
    per_step[step] = std::max(per_step[step], iteration);
  }
  Measurement m;
  m.steps = per_step.size();
  for (const auto& [step, n] : per_step) m.corrections += n;
  m.evaluations = m.corrections + static_cast<int>(m.steps);
  const std::string summary = read_file(std::filesystem::path(options.output_dir) / "summary.json");
  m.wall = json_number(summary, "wall_seconds", "status");
  for (const char* p : phases) m.seconds[p] = json_number(summary, p, "timings");
  return m;
}

void print(const Measurement& m, const std::string& title) {
  const double e = std::max(m.evaluations, 1);
  std::printf("contact benchmark: %s\n", title.c_str());
  std::printf("  steps %zu, Newton corrections %d (%.2f per step), residual evaluations %d\n",
              m.steps, m.corrections, m.steps ? double(m.corrections) / double(m.steps) : 0.0,
              m.evaluations);
  std::printf("  wall %.3f s, %.4f s per residual evaluation\n", m.wall, m.wall / e);
  std::printf("  %-14s %10s %14s %10s\n", "phase", "seconds", "s/evaluation", "share");
  for (const char* p : phases)
    std::printf("  %-14s %10.3f %14.5f %9.1f%%\n", p, m.seconds.at(p), m.seconds.at(p) / e,
                100.0 * m.seconds.at(p) / m.wall);
  const double mortar = m.seconds.at("search") + m.seconds.at("mortar");
  std::printf("  (search + mortar) / bulk assembly = %.3f\n",
              m.seconds.at("assembly") > 0.0 ? mortar / m.seconds.at("assembly") : 0.0);
}

/// A copy of the input beside it (so that its mesh path still resolves) with the friction
/// of every interface removed.
std::filesystem::path frictionless_copy(const std::filesystem::path& input) {
  YAML::Node root = YAML::LoadFile(input.string());
  int removed = 0;
  if (root["interfaces"])
    for (auto itf : root["interfaces"])
      if (itf["friction"]) removed += itf.remove("friction") ? 1 : 0;
  if (removed == 0) throw std::invalid_argument(input.string() + " has no friction to remove");
  std::string name = input.stem().string();
  name.append("_frictionless.yaml");
  const auto copy = input.parent_path() / name.insert(0, 1, '.');
  std::ofstream out(copy);
  out << root << "\n";
  if (!out) throw std::runtime_error("cannot write " + copy.string());
  return copy;
}

/// MPI for the benchmark's lifetime, so that each run's PETSc session (initialized and
/// finalized inside seam::app::run) leaves it open for the next run.
struct MpiLifetime {
  int was_initialized = 0;
  MpiLifetime(int& argc, char**& argv) {
    MPI_Initialized(&was_initialized);
    if (!was_initialized) MPI_Init(&argc, &argv);
  }
  ~MpiLifetime() {
    if (!was_initialized) MPI_Finalize();
  }
  MpiLifetime(const MpiLifetime&) = delete;
  MpiLifetime& operator=(const MpiLifetime&) = delete;
};

int run_contact_bench(int argc, char** argv) {
  MpiLifetime mpi(argc, argv);
  seam::app::RunOptions options;
  options.quiet = true;
  bool compare = false;
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
    } else if (a == "--compare-frictionless") {
      compare = true;
    } else if (a == "--") {
      for (++i; i < argc; ++i) options.petsc_args.emplace_back(argv[i]);
    } else if (a == "--help" || a == "-h") {
      std::printf("usage: seam-bench contact --input FILE.yaml [--output DIR] "
                  "[--compare-frictionless] [-- PETSc options]\n"
                  "  --compare-frictionless: run the input again without friction and print\n"
                  "  the cost of friction (iterations per step, time per evaluation).\n");
      return 0;
    } else {
      throw std::invalid_argument("unknown option " + a);
    }
  }
  if (options.input.empty()) throw std::invalid_argument("--input FILE.yaml is required");
  if (options.output_dir.empty())
    options.output_dir = (std::filesystem::temp_directory_path() / "seam_contact_bench").string();
  const Measurement with = measure(options, argc, argv);
  print(with, options.input);
  if (!compare) return 0;

  seam::app::RunOptions plain = options;
  const auto copy = frictionless_copy(options.input);
  plain.input = copy.string();
  plain.output_dir = options.output_dir + "_frictionless";
  Measurement without;
  try {
    without = measure(plain, argc, argv);
  } catch (...) {
    std::filesystem::remove(copy);
    throw;
  }
  std::filesystem::remove(copy);
  print(without, options.input + " without friction");
  const auto per = [](const Measurement& m, const char* p) {
    return m.seconds.at(p) / std::max(m.evaluations, 1);
  };
  const auto per_step = [](const Measurement& m) {
    return m.steps ? double(m.corrections) / double(m.steps) : 0.0;
  };
  std::printf("friction / frictionless:\n");
  std::printf("  Newton corrections per step  %8.2f %8.2f  ratio %.2f\n", per_step(with),
              per_step(without), per_step(without) > 0 ? per_step(with) / per_step(without) : 0.0);
  std::printf("  s per residual evaluation    %8.4f %8.4f  ratio %.2f\n",
              with.wall / std::max(with.evaluations, 1),
              without.wall / std::max(without.evaluations, 1),
              (with.wall / std::max(with.evaluations, 1)) /
                  (without.wall / std::max(without.evaluations, 1)));
  for (const char* p : {"mortar", "condensation", "linear_solve"})
    std::printf("  %-28s %8.4f %8.4f  ratio %.2f\n", (std::string(p) + " s/evaluation").c_str(),
                per(with, p), per(without, p),
                per(without, p) > 0 ? per(with, p) / per(without, p) : 0.0);
  std::printf("  share of mortar + friction evaluation in an iteration: %.1f %% (frictionless "
              "%.1f %%)\n",
              100.0 * (with.seconds.at("search") + with.seconds.at("mortar")) / with.wall,
              100.0 * (without.seconds.at("search") + without.seconds.at("mortar")) / without.wall);
  return 0;
}

const seam::bench::Register reg{
    "contact", "phases of a contact run per Newton iteration (--input FILE)", &run_contact_bench};

} // namespace
