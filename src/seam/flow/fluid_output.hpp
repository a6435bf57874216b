#pragma once
// What a fluid run writes (CONTRACT.md, "Fluids"): the VTU fields `velocity` and `pressure`
// with the PVD collection, steps.csv and newton.csv with the solid's columns, forces.csv,
// errors.csv against an exact solution, summary.json. Rank 0 writes the tables; every rank
// writes the fields of its own cells as one VTU piece (with the .pvtu on more than one rank),
// from the owned and ghost values it holds, so the state is never gathered. probes.csv has the
// solid's columns and the fluid's velocity and pressure last, and ux..uz the mesh displacement
// (ALE; 0 on a fixed mesh) at the probe's point of the reference mesh, which moves with the mesh.
// The VTU holds the reference mesh and the point field `mesh_displacement` (warp by it for the
// current).
#include "seam/common/timer.hpp"
#include "seam/flow/fluid_layout.hpp"
#include "seam/flow/fluid_model.hpp"
#include "seam/io/config.hpp"
#include "seam/io/table.hpp"
#include "seam/io/vtu.hpp"
#include "seam/la/petsc.hpp"
#include "seam/problem/piece_grid.hpp"

#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace seam::problem {
class Checkpoints;
class RecordWriter;
} // namespace seam::problem

namespace seam::flow {

struct FluidErrors {
  double velocity_l2 = 0.0;
  double pressure_l2 = 0.0; ///< of p_h - p, less its mean for an enclosed flow
};

struct FluidStepRecord {
  int step = 0;
  double time = 0.0;
  int newton_iterations = 0;
  double residual = 0.0;
  std::vector<std::array<double, 3>> forces; ///< per force group, summed over ranks
  std::optional<FluidErrors> errors;
};

class FluidOutput {
public:
  /// With `restart` the tables and results.pvd continue from the checkpoint (output.hpp).
  FluidOutput(const io::Config& config, const FluidLayout& layout, const FluidModel& model,
              std::filesystem::path dir, bool quiet, const problem::Checkpoints* restart = nullptr);
  ~FluidOutput();

  PhaseTimers& timers() { return timers_; }
  const std::filesystem::path& directory() const { return dir_; }
  void newton(int step, int iteration, double residual, double increment);
  /// The linear solver as the run's header names it (summary.json's linear_solver).
  void set_linear_solver(std::string name) { linear_solver_ = std::move(name); }
  /// This rank's share of the tied interfaces (ranks_detail): slave facets, ghosted master
  /// facets, pairs, integration cells.
  void set_interface_counts(const std::array<double, 4>& counts) { interface_counts_ = counts; }
  /// The iterations of one linear solve (summed into summary.json's linear_iterations).
  void linear_iterations(int n) {
    linear_iterations_ += n;
    ++linear_solves_;
  }
  /// A converged step: the tables, and the fields if due (every n-th, and `force_fields`).
  /// `w` is ghosted and up to date; `mesh_displacement` the displacement of every mesh node
  /// (node-major, the same on every rank), or empty for a fixed mesh. Collective.
  void step(const FluidStepRecord& r, const la::Vector& w,
            std::span<const double> mesh_displacement, bool force_fields);
  /// summary.json. Collective.
  void finish(bool converged, int n_steps);
  /// The output counters in a checkpoint (results.pvd's entries so far).
  void write_checkpoint(problem::RecordWriter& out) const;

private:
  void write_fields(int step, double time, std::span<const double> local,
                    std::span<const double> mesh_displacement);
  /// The pressure at every point of this rank's piece from the local vector form (linear on
  /// each cell).
  std::vector<double> nodal_pressure(std::span<const double> local) const;

  const io::Config& config_;
  const FluidLayout& layout_;
  const FluidModel& model_;
  std::filesystem::path dir_;
  bool quiet_;
  PhaseTimers timers_;
  double start_wall_;
  double start_time_; // the simulated time where the stepping began (the time left)
  std::unique_ptr<io::CsvTable> steps_, newton_, forces_, errors_, probes_;
  struct Probe {
    std::array<double, 3> point;
    std::int32_t cell;
    std::array<double, 3> xi;
  };
  std::vector<Probe> located_;
  std::unique_ptr<io::PvdCollection> pvd_;
  // This rank's piece: the nodes of its cells (mesh numbering) and the cells over them.
  std::optional<problem::PieceGrid> grid_;
  std::optional<FluidErrors> last_errors_;
  long long linear_iterations_ = 0, linear_solves_ = 0;
  std::string linear_solver_;
  std::vector<std::array<double, 3>> last_forces_;
  std::array<double, 4> interface_counts_{};
};

} // namespace seam::flow
