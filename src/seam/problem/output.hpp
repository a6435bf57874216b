#pragma once
// Everything a run writes (CONTRACT.md, "Output directory"): VTU/PVTU pieces and the PVD
// collection, steps.csv, newton.csv, reactions.csv, probes.csv, interfaces.csv and
// summary.json. Rows are flushed per step, so a failed run keeps every converged step.
#include "seam/common/timer.hpp"
#include "seam/io/config.hpp"
#include "seam/io/table.hpp"
#include "seam/io/vtu.hpp"
#include "seam/la/petsc.hpp"
#include "seam/meshtying/tied_interface.hpp"
#include "seam/problem/discretization.hpp"
#include "seam/problem/model.hpp"
#include "seam/problem/piece_grid.hpp"

#include <array>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace seam::io {
class Json;
}

namespace seam::problem {

struct StepRecord {
  int step = 0;
  double time = 0.0;
  int newton_iterations = 0;
  double residual = 0.0;
  int active_nodes = 0;
  int slip_nodes = 0;
  double kinetic_energy = 0.0;
  double internal_energy = 0.0;
  double external_work = 0.0;
  std::array<double, 3> momentum{};
  std::array<double, 3> angular_momentum{};
};

struct NewtonRecord {
  int step = 0;
  int iteration = 0;
  double residual = 0.0;
  double increment = 0.0;
  int active_set_changes = 0;
};

/// One slave node's row of interface_<name>.csv, computed by the rank that owns the node;
/// the rows go to rank 0 only to be written (Output: O(interface) there once per written
/// step).
struct InterfaceNodeRow {
  enum Status : std::int32_t { inactive = 0, stick = 1, slip = 2, tied = 3 };
  std::int64_t order = 0; ///< the row's place in the file, the same on any number of ranks
  std::int64_t node = 0;  ///< node id in the mesh as read
  double x[3] = {0.0, 0.0, 0.0}, u[3] = {0.0, 0.0, 0.0};
  double gap = 0.0, normal = 0.0, tangential = 0.0;
  std::int32_t status = inactive, pad = 0;
};

/// A contact interface's state at a converged step: the totals and the per-slave-node status
/// arrays the same on every rank; the multiplier vectors and the node rows only of the slave
/// nodes this rank owns (their normals and displacements are read by their owners only).
struct ContactReport {
  std::string name;
  std::vector<std::int32_t> slave_nodes; ///< mesh nodes
  /// Multiplier vector, dim per slave node: set at the nodes this rank owns, zero elsewhere.
  std::vector<double> lambda;
  std::vector<char> status;         ///< contact::NodeStatus: 0 inactive, 1 stick, 2 slip
  std::vector<double> weighted_gap; ///< g~_j
  std::vector<char> active;
  std::vector<char> owned;             ///< per slave node: this rank owns it
  std::vector<InterfaceNodeRow> rows;  ///< the rows of the slave nodes this rank owns
  double normal_force = 0.0;           ///< sum_j D_jj lambda_n,j
  double contact_area = 0.0;           ///< sum of D_jj over the active nodes
  double tangential_force = 0.0;       ///< |sum_j D_jj lambda_t,j|
  double frictional_dissipation = 0.0; ///< cumulative frictional work up to this step
  int active_nodes = 0;
  int slip_nodes = 0;
  int slave_elements = 0, master_elements = 0, candidate_pairs = 0;

  // The distribution of the slave elements over the ranks in this step (parallel.csv).
  double work_min = 0.0, work_mean = 0.0, work_max = 0.0; ///< per-rank work of the step
  bool redistributed = false; ///< the slave elements were redistributed after this step
  // This rank's share (different on every rank; summary.json ranks_detail).
  int local_slave_elements = 0;
  int local_master_ghosts = 0; ///< distinct master facets its candidate pairs reach
  /// Master facets this rank searched at the last search: those ghosted to it by the
  /// distributed search, the whole master surface otherwise.
  int local_master_received = 0;
  /// Self contact: surface facets this rank searched at the last search (its own and those
  /// ghosted to it), and the surface's facets.
  int local_surface_received = 0;
  /// Self contact, at the last search: the pairs this rank received to decide their roles
  /// (those of the groups of pairs it decides), and the oriented pairs it received back.
  std::int64_t local_self_pairs_received = 0, local_self_pairs_returned = 0;
  std::int64_t local_self_groups = 0; ///< the groups of pairs whose roles it decided then
  int self_label_rounds = 0;          ///< rounds the groups' labels took then (every rank)
  int surface_facets = 0;
  /// Ghost exchanges and searches of the distributed search so far.
  std::int64_t local_ghost_exchanges = 0;
  std::int64_t local_searches = 0;
  std::int64_t local_pairs = 0;
  std::int64_t local_integration_cells = 0;
  /// Slave nodes with nonzero mortar sums that this rank owns, sums and decides, and the nodal
  /// records it sent to the owners, at the last evaluation.
  std::int64_t local_contact_nodes = 0;
  std::int64_t local_nodal_records = 0;
  /// The interface nodes whose displacements this rank's evaluation scattered at the last
  /// evaluation (all contact interfaces; set on the first report only), and all of them.
  std::int64_t local_nodes_gathered = 0;
  std::int64_t interface_nodes = 0;
  /// Master facets (surface facets of self contact) and nodes the integration of this rank
  /// read at the last evaluation, and the slave nodes whose averaged normals it computed.
  std::int64_t local_master_facets_read = 0;
  std::int64_t local_normals = 0;
  /// The slave nodes this rank owns (it decides their status, checkpoints their state).
  std::int64_t local_owned_nodes = 0;
  /// Facets of the contact sides this rank holds (slave and master facets, a self-contact
  /// surface once: today the whole sides), and those of them whose nodes its scatter all
  /// brought at the last evaluation (its slave elements, their normal rings, its held master
  /// facets and ghosts: what it would hold with the sides distributed).
  std::int64_t local_side_facets_held = 0;
  std::int64_t local_side_facets_read = 0;
  /// The slave facets among them (a self-contact surface counted once, as a slave side).
  std::int64_t local_slave_facets_held = 0;
  /// Energy-momentum contact: the entries of the discrete gradients this rank sent to the slave
  /// nodes' owners and those it received, since the start of the run (or the restart).
  std::int64_t local_em_entries_sent = 0, local_em_entries_received = 0;
  /// Self contact: the facets' role changes so far within a step attempt and between steps
  /// (ContactSearch::role_changes; the same on every rank), and the pairs of a converged step
  /// found again at the next step's first search with the roles exchanged.
  std::int64_t role_changes_within_step = 0, role_changes_between_steps = 0;
  std::int64_t role_changes_persisting = 0;
};

/// The rows of all ranks on rank 0 in their order (empty on the other ranks). Collective.
std::vector<InterfaceNodeRow> rows_on_root(const Comm& comm,
                                           const std::vector<InterfaceNodeRow>& rows);

/// A probe located in the mesh: the cell that contains it and its reference coordinates.
struct LocatedProbe {
  std::array<double, 3> point{};
  std::int32_t cell = -1;
  std::array<double, 3> xi{};
};

/// Where a probe is evaluated on a distributed (or replicated) mesh: every rank looks among
/// `cells` (those it assembles, which together are the mesh); the cell the whole-mesh search
/// would pick (inside, then lowest id `cell_gid`; else the nearest within the tolerance) wins.
/// Returns the probe with its cell (local) and reference point on the winning rank, cell -1
/// elsewhere; a probe outside the mesh fails at its mark on every rank. Collective.
LocatedProbe locate_probe(const mesh::Mesh& mesh, std::span<const std::int32_t> cells,
                          const std::function<std::int64_t(std::int32_t)>& cell_gid,
                          const io::Probe& probe, Comm comm);

/// The entries of summary.json's ranks_detail that every run writes (CONTRACT.md), in this
/// order in a rank's record `d`: cells, ghost_cells, slave_elements, master_ghosts, pairs,
/// integration_cells, peak_rss_mb, interface_cells, owned_nodes, ghost_nodes, nodes. Put into
/// `e` (a JSON object), with `rank`.
constexpr std::size_t n_rank_detail_basics = 11;
void put_rank_detail_basics(io::Json& e, int rank, const double* d);

class Checkpoints;
class RecordWriter;
/// Writes this rank's piece of the fields of a step: results_NNNNN.vtu on one rank, else
/// one piece per rank and the .pvtu that lists them (rank 0). Returns the file the PVD
/// collection refers to. Collective.
std::string write_step_fields(const std::filesystem::path& dir, int step, const io::VtuPiece& piece,
                              Comm comm);

class Output {
public:
  /// With `restart` the tables continue: their rows after the checkpoint's step are dropped,
  /// new rows are appended, and results.pvd continues with the checkpoint's entries.
  Output(const io::Config& config, const Discretization& disc, const Model& model,
         const std::vector<meshtying::TiedInterface>& tied, std::filesystem::path dir, bool quiet,
         const Checkpoints* restart = nullptr);
  ~Output();

  PhaseTimers& timers() { return timers_; }
  const std::filesystem::path& directory() const { return dir_; }

  /// "seam: warning: MESSAGE" on the terminal (stderr of rank 0) when it is not quiet.
  void warning(const std::string& message) const;
  /// "  MESSAGE" on the terminal (stdout of rank 0, within the Newton iterations) when it is
  /// not quiet: what an iteration did beyond its row, such as a shortened correction.
  void note(const std::string& message) const;
  /// One Newton iteration (newton.csv; the terminal table when it is not quiet).
  void newton(const NewtonRecord& r);
  /// One linear solve of a Newton system and its Krylov iterations (a direct solve counts
  /// one), and whether it set up its preconditioner (a factorization, GAMG's hierarchy):
  /// summed into summary.json's linear_solves, linear_iterations and preconditioner_builds.
  void linear_solve(int iterations, bool built) {
    ++linear_solves_;
    linear_iterations_ += iterations;
    if (built) ++preconditioner_builds_;
  }
  /// The direct solver's symbolic analyses so far and the ordering of its next one
  /// (la::LinearSolver::symbolic_analyses, ordering): summary.json's symbolic_analyses and
  /// factor_ordering.
  void factorizations(int analyses, std::string ordering) {
    symbolic_analyses_ = analyses;
    factor_ordering_ = std::move(ordering);
  }
  /// A converged step: steps.csv, reactions.csv, probes.csv, and the fields if the step is due
  /// (every n-th, and always `force_fields`). `reactions` holds dim values per reaction region
  /// (summed over ranks), `u` and `v` are ghosted and up to date, `multipliers` holds per
  /// mesh-tying interface the Lagrange multiplier of every slave node (dim values each, the
  /// same on every rank). Collective.
  void step(const StepRecord& r, const la::Vector& u, const la::Vector* v,
            std::span<const double> reactions, const std::vector<std::vector<double>>& multipliers,
            bool force_fields);
  /// The contact state written with the next step() (and in summary.json).
  void contact_state(std::vector<ContactReport> reports) { contact_ = std::move(reports); }
  /// The initial state (step 0) as fields only. Collective.
  void initial(const la::Vector& u);
  /// The output counters in a checkpoint (results.pvd's entries so far).
  void write_checkpoint(RecordWriter& out) const;
  /// summary.json; `converged` false for a run that gave up. Collective.
  void finish(bool converged, int n_steps);

private:
  /// Interface state of one step. Per slave node of the rank's side (valid on the nodes it
  /// owns); the totals on every rank; the node rows on rank 0 (when asked for).
  struct InterfaceState {
    std::vector<double> lambda;       ///< dim per slave node
    std::vector<double> gap;          ///< normal part of D u_S - M u_M per slave node
    std::vector<double> displacement; ///< dim per slave node
    double normal_force = 0.0, tangential_force = 0.0;
    int tied = 0;
    std::vector<InterfaceNodeRow> rows; ///< rank 0: every slave node, by node id
  };
  /// Collective.
  std::vector<InterfaceState> interface_states(const la::Vector& u,
                                               const std::vector<std::vector<double>>& multipliers,
                                               bool node_rows) const;
  /// Collective: the totals and (node_rows) the node rows of tied interface k.
  void summarize(std::size_t k, InterfaceState& s, bool node_rows) const;
  void write_interfaces(const StepRecord& r, const std::vector<InterfaceState>& states,
                        const std::vector<std::vector<InterfaceNodeRow>>& contact_rows,
                        bool write_nodes);
  /// interface_<name>.csv from the rows of every slave node (rank 0).
  void write_node_rows(const std::string& name, const std::vector<InterfaceNodeRow>& rows) const;
  void write_fields(int step, double time, const la::Vector& u, const la::Vector* v,
                    const std::vector<InterfaceState>& states);

  const io::Config& config_;
  const Discretization& disc_;
  const Model& model_;
  const std::vector<meshtying::TiedInterface>& tied_;
  std::vector<la::Gather> tied_gather_; ///< per tied interface: its slave, then master dofs
  std::vector<ContactReport> contact_;
  bool has_contact_ = false;
  std::vector<std::vector<char>> tied_rows_; // per interface and slave node: has a row of D
  std::filesystem::path dir_;
  bool quiet_;
  PhaseTimers timers_;
  double start_wall_;
  // Wall clock and simulated time where the stepping began (the estimate of the time left).
  double progress_wall_ = 0.0, progress_time_ = 0.0;
  long long linear_solves_ = 0, linear_iterations_ = 0, preconditioner_builds_ = 0;
  long long symbolic_analyses_ = 0;
  std::string factor_ordering_;
  std::vector<LocatedProbe> probes_;
  std::unique_ptr<io::CsvTable> steps_, newton_, reactions_, probes_table_, interfaces_, errors_,
      parallel_;
  std::vector<double> last_errors_; // l2, h1 of the last step, with an exact solution
  std::unique_ptr<io::PvdCollection> pvd_;
  int last_field_step_ = -1;
  // VTU piece of this rank (fixed topology): connectivity in VTK order over local nodes.
  std::optional<PieceGrid> grid_;
  std::vector<std::int32_t> cell_material_;
};

} // namespace seam::problem
