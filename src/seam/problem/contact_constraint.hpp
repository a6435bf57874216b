#pragma once
// Frictionless mortar contact solved by the semi-smooth Newton (primal-dual active set)
// method with the dual multipliers condensed (seed paper Sect. 4.2; ALGORITHMS.md §5;
// Popp et al. 2009, 2010; Hueeber & Wohlmuth 2005).
//
// Unknowns: the displacements d and one normal multiplier lambda_n,j per slave node (the
// contact traction is lambda_n,j n_j, so the frictionless condition lambda_t = 0 holds by
// construction). Nonlinear complementarity, with the nodal gap g_j = g~_j / D_jj,
//   C_j = lambda_n,j - max(0, lambda_n,j - c_n g_j) = 0,
// active set A = {j : lambda_n,j - c_n g_j > 0}. Each Newton iteration solves, for the new
// multipliers lambda^{k+1} and the increment dd, with K~ = K + d(B^T lambda^k)/dd,
//   K~ dd + B^T lambda^{k+1} = -r,   lambda_j^{k+1} = 0 (j in I),   dg~_j dd = -g~_j (j in A).
// The dual basis makes D diagonal, so the slave rows give lambda_j explicitly. At an active
// node j whose free (not prescribed) components span V, w = P_V n_j:
//   lambda_j^{k+1} = -w . (K~_j dd + r_j) / (D_jj w . n_j),
// which is substituted into the master rows (M_jl / (D_jj w.n_j)) n_j w^T (K~_j dd + r_j);
// the free rows of node j become the gap row and the equilibrium along the directions of V
// orthogonal to w, which carry no multiplier. In matrix form
//   (L K~ + G) dd = -L r  (with c_n g~_j in the gap rows),
// with L the identity on every other row. No saddle point, no tangent derivatives. L = I + dL
// is applied as K + dL K (dL has the rows of the active slave nodes and their master nodes
// only), so the condensation costs in proportion to the contact zone, not to K.
// With the modified slave basis of tri6/quad8 facets (d = T d~, Popp et al. 2012) the slave
// force is T^-T D lambda n; the slave rows are first combined by T^T (matrix P), which leaves
// D_jj lambda_j alone in row j: Ksys = L P (K + Kc~) with Kc~ the derivative of D lambda n.
//
// With standard multipliers (`multiplier: standard`, any interface) D is not diagonal and the
// multipliers stay unknowns: the same semi-smooth Newton step is solved as a saddle point,
//   [ K~  B^T ] [ dd          ]   [ -r       ]      B^T = d(contact force)/d lambda:
//   [ C   E   ] [ lambda^{k+1} ] = [ -c_n g~_A ],   slave k: D_jk n_j, master l: -M_jl n_j,
// with C = c_n dg~_j/dd, E = 0 on the active rows and C = 0, E = (nodal weight) on the
// inactive ones (lambda_j = 0); the nodal weight D_j = sum_k D_jk = int N_j replaces D_jj.
//
// With friction and standard multipliers the multiplier lambda_j is a Cartesian vector (dim
// unknowns per slave node, B^T: D_jk e_c, -M_jl e_c); its rows are the gap row, one row per
// tangent of the linearized frictional condition (below, with the nodal weight D_j in place of
// D_jj) and lambda_j,c = 0 in prescribed components; inactive nodes lambda_j = 0. The slip
// increment then takes the full D: u~_j = sum_l (M_jl - M^n_jl) x_l - sum_k (D_jk - D^n_jk) x_k
// (against a rigid plane D_j P (x_j - x_j^n - (c - c^n))).
//
// With friction (contact_friction.cpp) the multiplier of a slave node is a Cartesian vector
// lambda_j in the span V of its free directions, recovered from all its free slave rows,
//   lambda_j^{k+1} = -P_V (K~_j dd + r_j) / D_jj,
// and passed to the master rows by M_jl / D_jj. The free rows of an active node become the gap
// row and one row per tangent t_i of the linearized frictional condition (contact/friction.hpp)
//   alpha . (lambda^{k+1} - lambda^k) + beta . dd = -C_i,
// multiplied by -D_jj so that alpha . lambda^{k+1} turns into rows of K~ and r (through L) and
// beta, the chained derivatives of n_j, the slip increment u~_j, D_jj and g~_j, into G.
// Every stick/slip decision is taken in each Newton iteration together with the normal one.
#include "seam/common/timer.hpp"
#include "seam/contact/active_set_cycles.hpp"
#include "seam/contact/contact_interface.hpp"
#include "seam/contact/friction.hpp"
#include "seam/io/config.hpp"
#include "seam/la/petsc.hpp"
#include "seam/parallel/facet_distribution.hpp"
#include "seam/problem/contact_search.hpp"
#include "seam/problem/discretization.hpp"
#include "seam/problem/model.hpp"
#include "seam/problem/output.hpp"

#include <algorithm>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace seam::parallel {
class HolderPublisher;
}

namespace seam::problem {

class RecordWriter;
class Checkpoints;

class ContactConstraint {
public:
  ContactConstraint(const io::Config& config, const Discretization& disc, const Model& model);
  /// Not copied nor moved: the interfaces point at reference_x_.
  ContactConstraint(const ContactConstraint&) = delete;
  ContactConstraint& operator=(const ContactConstraint&) = delete;

  bool active() const { return !sides_.empty(); }

  /// Energy-momentum contact (`integrator: energy_momentum`; docs/contact_dynamics.md §4): on
  /// the frictionless two-body and self-contact interfaces of line2 faces the contact force is
  /// -sum_j lambda_j grad_d g~_j(x_n, x_{n+1}), the discrete gradient of the weighted gaps, and
  /// every Newton step is the saddle point with B^T = grad_d g~ (standard or dual multipliers
  /// alike). start_step gives the displacement at the start of the step, before the first
  /// evaluate() of the step. Collective.
  void start_step(const la::Vector& u_n);
  /// Interfaces with the discrete-gradient force, and those that keep the force of the end of
  /// the step (friction against a rigid obstacle, quadratic faces).
  int n_discrete_gradient() const;
  int n_end_of_step() const;
  /// After a converged energy-momentum step, at its last evaluate(): the energy the step gained
  /// through contact, G = sum_j e_j with e_j = max(0, -lambda_j g~_j(x_n)), over the slave nodes
  /// of the discrete-gradient interfaces between deformable bodies (a node that started the step
  /// beyond the other surface and took contact, or one held active with lambda_j < 0 from a
  /// positive gap) and, against rigid obstacles, over the nodes with lambda_j < 0; d += sum_j
  /// e_j grad g~_j(x_{n+1}) between bodies, `obstacle` the same against obstacles (mesh dofs as
  /// global rows; contact_impact.cpp, docs/contact_dynamics.md §5). Collective.
  struct ImpactGain {
    double gain = 0.0;
    int nodes = 0; ///< slave nodes whose e_j exceeds 1e-6 of G
  };
  ImpactGain impact_gain(la::Vector& d, la::Vector& obstacle) const;

  /// The state at displacement u (ghosted, up to date) and time t with the current
  /// multipliers: geometry, search, D, g~; the active set from the complementarity function.
  /// Returns the number of nodes whose status changed against the previous iteration.
  /// `first` marks the first iteration of a step; `retrial` a shortened correction of the
  /// same iteration (line search) after an evaluation that kept every status: the statuses
  /// decided there replace that evaluation's for the cycling guard. Collective.
  int evaluate(const la::Vector& u, double t, bool first, PhaseTimers& timers,
               bool retrial = false);
  /// r += contact force of the current multipliers; with `between_bodies_only` only that of
  /// the interfaces between deformable bodies (two bodies, self contact), not of rigid
  /// obstacles. Collective.
  void add_force(la::Vector& r, bool between_bodies_only = false) const;
  /// Complementarity residual in force units: c_n g~_j on active nodes, D_jj lambda_n,j on
  /// inactive ones. Same on every rank.
  double complementarity_norm() const;

  /// The Newton system at the last evaluate(): Ksys = L (K + Kc) + G, rsys = L r with the gap
  /// rows c_n g~_j (the caller negates it). K and r are the bulk ones (r without contact).
  /// The linearization is timed as "mortar", the matrix products as "condensation".
  void condense(const la::Matrix& K, const la::Vector& r, la::Matrix& Ksys, la::Vector& rsys,
                PhaseTimers& timers);
  /// The new multipliers from the solution dd of the condensed system. Collective.
  void recover(const la::Matrix& K, const la::Vector& r, const la::Vector& dd);

  /// Standard multipliers on some interface: each Newton step is the saddle point above
  /// instead of condense / recover.
  bool saddle_point() const { return saddle_point_; }
  /// Solves the saddle point at the last evaluate() for dd and the new multipliers. `minus_r`
  /// is -r (bulk residual without contact, zero Dirichlet rows), `dirichlet` the fixed
  /// displacement dofs and `g`, if given, their prescribed increments. Returns false if the
  /// linear solver failed. Collective.
  bool solve_saddle_point(const la::Matrix& K, const la::Vector& minus_r,
                          std::span<const PetscInt> dirichlet, const la::Vector* g,
                          la::LinearSolver& solver, la::Vector& dd, PhaseTimers& timers);

  /// After a converged step, before reports(): each interface's per-rank work of the step
  /// (CPU time of its mortar evaluation and linearization, or its integration cells) against
  /// parallel.rebalance_tolerance (the seed's eq. 21); an independently distributed interface
  /// whose max/min exceeds it is redistributed for the next step. Collective.
  void balance();

  /// Multipliers of the last converged step (save) are restored after a failed attempt.
  void save();
  void restore();
  /// The state of the last converged step in a checkpoint, and back (contact_checkpoint.cpp).
  /// write_checkpoint is collective.
  /// read_checkpoint returns what the terminal should say of it (e.g. whether the slave
  /// elements keep the checkpoint's cut).
  void write_checkpoint(RecordWriter& out) const;
  std::vector<std::string> read_checkpoint(const Checkpoints& in);

  int n_active() const;
  /// Whether no interface carries friction.
  bool frictionless() const {
    return std::none_of(sides_.begin(), sides_.end(), [](const Side& s) { return s.friction; });
  }
  /// Whether a rigid obstacle of some interface has a prescribed motion (it can do work).
  bool moving_obstacle() const {
    return std::any_of(sides_.begin(), sides_.end(),
                       [](const Side& s) { return s.itf.rigid() && s.itf.obstacle_moves(); });
  }
  /// Whether the active set at the last evaluate() differs from the one of the last converged
  /// step (save()): a contact opened or closed in the step. Same on every rank.
  bool set_changed() const;
  /// One line per interface for `seam check`.
  std::vector<std::string> describe() const;
  /// One line per interface: what every rank still holds whole of it, and what is
  /// distributed (printed at the start of a run).
  std::vector<std::string> held_whole() const;
  /// Per interface, the state for the output files after balance(): the totals on every
  /// rank, the rows of interface_<name>.csv of the slave nodes around each rank's slave
  /// elements (read through its own displacement scatter, made anew first when balance()
  /// redistributed the elements). Collective.
  std::vector<ContactReport> reports(const la::Vector& u);
  /// Active nodes in stick (friction) and in slip (every active node without friction).
  int n_slip() const;
  /// Nodes that the cycling guard froze between stick and slip and that were accepted within
  /// the hysteresis band of their friction cone at the last evaluate() (contact_friction.cpp).
  int n_on_cone() const;
  /// Nodes that the cycling guard froze between stick and slip and whose frozen status violates
  /// its condition beyond the band at the last evaluate(): each counts as a change.
  int n_inconsistent() const;
  /// Nodes that a frozen or held set kept active but that had no pair at the last evaluate()
  /// (D_jj = 0: no gap row, no force column) and were released; counted among its changes.
  /// Same on every rank.
  int n_released() const { return released_; }
  /// The node (its id in the mesh as read) at which a slave surface folded back onto itself at
  /// the last evaluate() (the normals of its facets cancel), -1 if none: an unusable iterate,
  /// evaluated no further, whose step Newton cuts. Same on every rank. At the first evaluate()
  /// of the run (the mesh as read) such a node is an InputError instead.
  std::int64_t folded_node() const { return folded_node_; }

  /// Diagnostics and tests of the linearization. While the sets are held, evaluate() keeps
  /// every node's status (active, stick, slip) and tangent frame as they are, so that the
  /// nonlinear system is a smooth function of the state whose derivative the Newton matrix is.
  void hold_sets(bool hold);
  /// The multipliers of all sides, concatenated (Cartesian, dim per slave node, on frictional
  /// sides; one per slave node otherwise), and their replacement.
  std::vector<double> multipliers() const;
  void set_multipliers(std::span<const double> lambda);
  /// The constraint functions the Newton step linearizes at the last evaluate(), laid out as
  /// multipliers(): on a frictional side per node, inactive: lambda_j; active: g~_j in
  /// component gap_component, t_i . C_t (contact/friction.hpp) in tangent_component[i] and
  /// lambda_j,c in prescribed components c. Frictionless sides: lambda_j or g~_j.
  std::vector<double> constraint_values() const;

  /// Diagnostics (docs/contact_dynamics.md, "Diagnosing a stalled Newton step"), one line
  /// per side: candidate pairs (and a hash of the oriented pairs), overlapping gap blocks at
  /// x_{n+1} (and a hash of their slave rows and dofs), active nodes, nodes with a gap row,
  /// whether the pairs are held. At the last evaluate(); np = 1 figures on a distributed side
  /// are this rank's.
  std::vector<std::string> trace() const;
  /// The slave node behind entry k of multipliers() / constraint_values(): interface, mesh
  /// node, whether active, its multiplier, g~_j and D_jj.
  std::string describe_multiplier(std::size_t k) const;
  /// The interface side(s) and status of a mesh node ("" if it is on no slave side).
  std::string describe_node(std::int32_t node) const;
  /// |A x - b| / |b| of the last saddle-point solve, measured only while SEAM_NEWTON_CHECK is
  /// set (-1 otherwise).
  double last_solve_residual() const { return last_solve_residual_; }

private:
  /// Free-direction data of an active slave node: w, the row that carries the gap and the
  /// tangent rows.
  struct NodeFrame {
    double w[3] = {0, 0, 0};
    double wn = 0.0;
    int gap_component = 0;
    int n_tangents = 0;
    int tangent_component[2] = {0, 0};
    double tangent[2][3] = {{0, 0, 0}, {0, 0, 0}};
  };
  /// A slave facet as it crosses the ranks (a slave side held in part with the independent
  /// distribution): its id, facet type and node ids in the facet's order, filed under `key`
  /// (its own id in the facet directory, the id of one of its nodes in the ring directory).
  struct SlaveFacet {
    std::int64_t key = 0;
    std::int64_t id = 0;
    std::int32_t type = 0;
    std::int32_t n_nodes = 0;
    std::int64_t nodes[fem::max_facet_nodes] = {};
  };
  struct Side {
    explicit Side(contact::ContactInterface i) : itf(std::move(i)) {}
    contact::ContactInterface itf;
    double c_n = 0.0;
    contact::NodalValues part; ///< this rank's share
    /// D_jj (the nodal weight with standard multipliers) and g~_j: summed on the owner of
    /// slave node j, which decides its status, then published to every rank.
    std::vector<double> D, gap;
    /// The global ids of the slave side's facets and nodes (crossing the ranks).
    SideIds slave_ids;
    std::vector<std::int64_t> node_keys; ///< node id of slave node j (the mesh as read)
    std::vector<int> node_owners;        ///< the rank owning each slave node
    struct {
      std::int64_t sent = 0;    ///< nodal records sent to the owners at the last evaluate
      std::int64_t decided = 0; ///< slave nodes with nonzero sums this rank decided then
    } nodal;
    std::vector<double> lambda, lambda_saved;
    std::vector<char> active, active_previous;
    std::vector<char> active_accepted; ///< the active set of the last converged step
    contact::ActiveSetCycles cycles;   ///< the sets of the current step, for the cycling guard
    std::vector<char> dirichlet;       ///< per slave node and component
    contact::Linearization lin;
    /// Modified slave basis (tri6/quad8): T^-1 as triplets (side-local), empty when T = I.
    std::vector<mortar::Triplet> T_inverse;
    double area = 0.0;
    bool frozen = false; ///< active set frozen after cycling was detected in this step
    /// Saddle point: the global multiplier row of every slave node the side holds (numbered by
    /// the node's owner from lm_first, published to its holders: number_multipliers), and the
    /// first row of the slave nodes this rank owns.
    std::vector<PetscInt> lm_index;
    PetscInt lm_first = 0;
    double ncp_norm2 = 0.0; ///< complementarity residual squared (force units)

    // Distribution of the slave facets over the ranks.
    std::vector<local_index> bulk_facets; ///< slave facets whose cell this rank assembles
    std::unique_ptr<parallel::FacetDistribution> distribution; ///< independent only
    /// Two-body and self-contact interfaces: the search distributed over the ranks (facets
    /// ghosted).
    std::unique_ptr<ContactSearch> search;
    /// The master side held in part (master_held_in_part): the facets of the whole side, and
    /// the node (mesh node, or outside node numbered after them) of every node of the ghosts
    /// of the last search.
    bool master_in_part = false;
    int master_facets = 0;
    /// The slave side held in part (slave_held_in_part): the facets of its own and ghost cells
    /// and the nodal arrays of their nodes; the slave facets of the whole side.
    bool slave_in_part = false;
    int slave_facets = 0;
    /// A slave side held in part with the independent distribution: the slave region of the
    /// mesh (the facets of the rank's own and ghost cells), from which the held facets are
    /// taken at each distribution (hold_slave_part), the others coming from the directories:
    /// the rank id % size keeps the slave facets of id `id` (facet_directory) and those
    /// around the node of id `id` (ring_directory) of the facets of the ranks' own cells.
    const mesh::Region* slave_region = nullptr;
    /// A self-contact surface held in part: its region in the mesh (slave_region points here).
    std::shared_ptr<const mesh::Region> surface_region;
    std::vector<SlaveFacet> facet_directory, ring_directory;
    /// The ids of the slave facets of this rank's own cells (sorted): the bulk share.
    std::vector<std::int64_t> own_facet_ids;
    /// A slave side held in part against a rigid obstacle, without a modified slave basis: the
    /// normals are the obstacle's at each node (no ring of facets around a node is read), so
    /// after a distribution a rank holds the facets it evaluates and one facet of each slave
    /// node it owns (hold_slave_part), and the owner of a slave node writes its output row.
    bool compact = false;
    /// A slave side held in part: the owners publish to the ranks that hold each node
    /// (publish()).
    std::shared_ptr<const parallel::HolderPublisher> holders;
    std::vector<std::int32_t> ghost_nodes;
    /// Self contact: the oriented pairs of the searches of the current step (newest last, at
    /// most ContactSearch::max_pair_period + 1) and the pairs held for the rest of the step
    /// once the search returned to an earlier set (pair cycling guard, see search()).
    /// Self contact: the pair sets of the step's searches (over all ranks) with this rank's
    /// pairs of each.
    struct PairsFound {
      ContactSearch::PairSet set;
      std::vector<FacetIdPair> pairs;
    };
    std::deque<PairsFound> pair_history;
    std::vector<mortar::CandidatePair> held_pairs;
    bool pairs_held = false;
    bool distributed = false;  ///< the first distribution is done
    double work_seconds = 0.0; ///< CPU time of this rank's evaluation in the current step
    parallel::BalanceDecision balance;
    bool redistributed = false; ///< in the last balance()
    struct {
      int slave_elements = 0;   ///< this rank's, in the last balanced step
      int master_ghosts = 0;    ///< distinct master facets of its pairs
      int master_received = 0;  ///< master facets it searched at the last search
      int surface_received = 0; ///< self contact: surface facets it searched then
      /// Self contact, at the last search: pairs it received to decide, and back.
      std::int64_t self_pairs_received = 0, self_pairs_returned = 0, self_groups = 0;
      int label_rounds = 0; ///< self contact: rounds of the group labels at the last search
      std::int64_t ghost_exchanges = 0; ///< of the distributed search, so far
      std::int64_t searches = 0;        ///< of the distributed search, so far
      std::int64_t candidates = 0;      ///< candidate pairs of all ranks
    } share;

    // Friction: lambda holds dim values per slave node (Cartesian), status the
    // contact::NodeStatus of every node (active mirrors it).
    bool friction = false;
    contact::FrictionLaw law;
    std::vector<char> status, status_previous;
    std::vector<char> status_accepted; ///< the statuses of the last converged step
    std::vector<char> frozen_nodes;    ///< nodes whose status the cycling guard fixed in this step
    std::vector<double> slip;          ///< weighted slip increment u~ of the step, dim per node
    /// Current slave node positions in the modified basis (x~ = T^-1 x; x without one), dim
    /// per node, and the same at the last converged step.
    std::vector<double> x;
    std::vector<double> x_old;
    std::vector<double> D_diag;     ///< D_jj, summed over ranks (= D without coupling)
    std::vector<double> D_diag_old; ///< D_jj at the last converged step
    /// Standard multipliers: this rank's part of the entries D_jk, j != k, then.
    std::vector<mortar::Triplet> D_coupling_old;
    std::vector<contact::MortarEntry> M_old; ///< this rank's part of M then
    std::array<double, 3> plane_old{};       ///< rigid plane displacement then
    double dissipation = 0.0;                ///< frictional work up to the last converged step
    int on_cone = 0;      ///< frozen nodes accepted within the stick/slip band at the last evaluate
    int inconsistent = 0; ///< frozen nodes violating their condition beyond the band then
    bool has_old = false; ///< D_diag_old and M_old are set
    /// hold_sets(true): the frames of every node, kept until hold_sets(false).
    std::vector<NodeFrame> held_frames;

    // Energy-momentum contact: the force per unit multiplier -grad_d g~_j of the slave nodes
    // this rank owns (their entries, node j and mesh dof) and this rank's part of the
    // derivative of -sum_j lambda_j grad_d g~_j (mesh dofs), at the last evaluate().
    bool discrete_gradient = false;
    struct GradientEntry {
      std::size_t j = 0;
      std::int64_t dof = 0;
      double value = 0.0;
    };
    std::vector<GradientEntry> em_gradient;
    std::vector<contact::DofTriplet> em_tangent;
    /// Friction: G_j(x_mid) = sum_k D_jk x_mid,k - sum_l M_jl x_mid,l with the mean operators
    /// (dim per slave node, replicated).
    std::vector<double> em_gap_mid;
    /// The interface displacement of the last evaluate() (the tangent is built from it when
    /// a matrix is needed) and whether em_tangent belongs to it.
    std::vector<double> em_displacement;
    /// Per slave node (replicated): whether g~_j(x_{n+1}) has a nonzero gradient, i.e. a gap
    /// row in the Newton step (paired()).
    std::vector<char> em_row;
    bool em_tangent_current = false;
    /// Diagnostics (trace()): the overlapping gap blocks at x_{n+1} of the last evaluate()
    /// and a hash of their slave rows and dofs.
    std::size_t em_blocks = 0;
    std::uint64_t em_blocks_hash = 0;
    /// Pairs without a block then: dropped by the pre-check, without overlap, and of those
    /// with an unconverged projection (line2).
    long em_rejections[3] = {0, 0, 0};
    /// The entries of the discrete gradients this rank sent to the slave nodes' owners and
    /// those it received as an owner, summed over the evaluations of the run.
    std::int64_t em_entries_sent = 0, em_entries_received = 0;
  };
  NodeFrame frame(const Side& s, std::size_t j) const;
  /// Whether slave node j has a pair at the last evaluate(): a nodal weight D_jj above 1e-12
  /// of the side's largest (d_max), and with the discrete-gradient force also a gap row. Only
  /// such a node can be active: any other has no constraint row (a singular saddle point).
  static bool paired(const Side& s, std::size_t j, double d_max) {
    return s.D[j] > 1e-12 * d_max && (!s.discrete_gradient || s.em_row[j] != 0);
  }
  /// This rank's part of D_jj, g~_j (and on a frictional side D_jj without coupling, in
  /// D_diag) summed on the owners of the slave nodes (parallel::sum_on_owners): on return the
  /// owned nodes hold the sums, the others zero. Collective.
  void sum_nodal_values(Side& s) const;
  /// The owners' D, g~ (D_diag) and status decisions `next` (one per slave node) published to
  /// every rank (parallel::publish_from_owners). Collective.
  void publish_nodal_values(Side& s, std::vector<char>& next) const;
  /// The largest D_jj of the side (its owners' sums). Collective.
  double max_weight(const Side& s) const;
  /// The owners' values of the slave nodes of side s (`width` per node) to the ranks that hold
  /// the nodes: every rank on a side held whole (parallel::publish_from_owners), the holders
  /// on a side held in part (parallel::HolderPublisher). Returns the records this rank sent.
  /// Collective.
  std::size_t publish(const Side& s, std::span<double> values, int width) const;
  /// The discrete gradients of side s at the interface displacement u (x_{n+1}) and the start
  /// of the step, and with `tangent` the derivative of their force at the current multipliers
  /// (em_tangent, from the Hessians of the weighted gaps: only when a matrix is built;
  /// contact_energy_momentum.cpp). Collective.
  void evaluate_discrete_gradient(Side& s, std::span<const double> u, bool tangent);
  // Energy-momentum contact with friction (contact_energy_momentum_friction.cpp): the normal
  // part n_j . lambda_j of the Cartesian multiplier takes the discrete-gradient force, the
  // tangential part P_j lambda_j the work conjugate of the frame-indifferent slip increment
  // u~_j = G_j(dx) - theta_j x G_j(x_mid) over the mean operators D = (D^n + D^{n+1}) / 2,
  // M = (M^n + M^{n+1}) / 2 (G_j(y) = sum_k D_jk y_k - sum_l M_jl y_l).
  /// Visits this rank's entries of the mean operators: (slave node j, mesh node, weight) with
  /// the weight D_jk / 2 on slave node k and -M_jl / 2 on master node l, for the operators of
  /// x_{n+1} (this rank's part) and of x_n (the diagonal on the owner of j).
  void
  for_each_mean_operator(const Side& s,
                         const std::function<void(std::size_t, std::int32_t, double)>& visit) const;
  /// This rank's part of the tangential force of a frictional energy-momentum side (the mean
  /// operators' force of lambda_t and the couple on the owned nodes' rings), added to f (mesh
  /// dofs).
  void add_energy_momentum_friction_force(const Side& s, std::span<double> f) const;
  /// The normal multipliers: n_j . lambda_j on a frictional side, lambda_j otherwise.
  std::vector<double> normal_multipliers(const Side& s) const;
  /// P_j lambda_j (dim per slave node) of a frictional side.
  std::vector<double> tangential_multipliers(const Side& s) const;
  /// s.slip = u~_j of the step on the owners of the slave nodes, and em_gap_mid. Collective.
  void energy_momentum_slip(Side& s, std::span<const double> u_mesh) const;
  /// The derivative of the frictional energy-momentum force beyond -lambda_n (H / 2 + the
  /// correction's): the turning normal in lambda_n and P_j, the operators' derivatives and the
  /// couple's (in em_tangent), and the derivatives of D_j and of u~_j for the friction rows
  /// (in s.lin).
  void energy_momentum_friction_tangent(Side& s);
  /// This rank's columns of B^T for a frictional energy-momentum side.
  void energy_momentum_friction_columns(const Side& s, std::vector<PetscInt>& bi,
                                        std::vector<PetscInt>& bj, std::vector<double>& bv) const;
  // Friction (contact_friction.cpp).
  void init_friction(Side& s, const io::Interface& config, double c_n);
  /// Slip increments, stick/slip/inactive status with the cycling guard, complementarity
  /// residual. Returns the number of status changes.
  int evaluate_friction(Side& s, std::span<const double> u_mesh, bool first);
  contact::FrictionNode friction_node(const Side& s, std::size_t j) const;
  /// Frames and frictional rows (contact/friction.hpp) of the active nodes of side s.
  struct FrictionRows {
    std::vector<NodeFrame> frames;
    std::vector<std::array<contact::FrictionRow, 2>> rows;
  };
  FrictionRows friction_rows(const Side& s) const;
  /// This rank's part of the derivative of the tangent rows with respect to the displacements
  /// (the chained derivatives of n_j, u~_j, D_j and g~_j), times sign * D_j, in the rows
  /// row_of(j, i) (node j, tangent i).
  void friction_gradients(const Side& s, const FrictionRows& fr,
                          const std::function<PetscInt(std::size_t, int)>& row_of, double sign,
                          std::vector<PetscInt>& gi, std::vector<PetscInt>& gj,
                          std::vector<double>& gv) const;
  /// This rank's multiplier rows of a frictional side in the saddle point: C (columns
  /// displacements), E (columns multipliers) and the right-hand side of its owned rows.
  void saddle_friction(Side& s, std::vector<PetscInt>& ci, std::vector<PetscInt>& cj,
                       std::vector<double>& cv, std::vector<PetscInt>& ei,
                       std::vector<PetscInt>& ej, std::vector<double>& ev,
                       std::vector<double>& lm_rhs) const;
  /// The mean nodal weight D_jj > 0 of side s (each node counted by its owner): the weight of
  /// inactive rows outside the contact zone. Collective.
  double mean_weight(const Side& s) const;
  /// Saddle point: the multiplier rows of the slave nodes side s holds. The owner of a node
  /// numbers it (from s.lm_first, the nodes it owns in side order: node id order, the same on
  /// every part) and publishes the row to the node's holders. Collective.
  void number_multipliers(Side& s) const;
  /// This rank's rows of a frictional side in the condensed system (see the header comment).
  void condense_friction(Side& s, std::vector<char>& replaced, std::vector<PetscInt>& li,
                         std::vector<PetscInt>& lj, std::vector<double>& lv,
                         std::vector<PetscInt>& gi, std::vector<PetscInt>& gj,
                         std::vector<double>& gv, std::vector<PetscInt>& set_rows,
                         std::vector<double>& set_values, std::vector<PetscInt>& add_rows,
                         std::vector<double>& add_values) const;
  /// The frictional work of the current step, summed over the owners of the active nodes (the
  /// same on every rank). Collective.
  double dissipation_increment(const Side& s) const;
  /// Against a rigid obstacle: w_j = sum_k D_jk d_k with d_k = x~_k - x~_k^n - (c - c^n) the
  /// motion of slave node k relative to the obstacle in the step (D_jj d_j with dual
  /// multipliers); dim per node, replicated. Collective.
  std::vector<double> rigid_motion_weighted(const Side& s) const;
  void save_friction(Side& s);
  /// Linearizes side s at its multipliers and active set (s.lin) and appends this rank's part
  /// of the contact force tangent as global triplets.
  void linearize(Side& s, std::vector<PetscInt>& rows, std::vector<PetscInt>& cols,
                 std::vector<double>& values);
  /// The global dof of a mesh dof (node * dim + component; a node at or beyond the mesh's
  /// node count is an outside node).
  PetscInt global_dof(std::int64_t mesh_dof) const;
  /// The global dof of component c of node `node` (a mesh node or an outside node).
  PetscInt dof_of(std::int32_t node, int c) const;
  /// Collective. The node of every id in `ids` (node ids of the mesh as read of the ghosts of
  /// a master side held in part, of the slave facets sent to a slave side held in part): its
  /// mesh node if it is an interface node of this part, else an outside node, whose global
  /// dofs, owner and reference coordinates come from the directory (the rank id % size keeps
  /// those of the nodes of the master facets the ranks hand in and of the slave facets of
  /// their own cells).
  void map_nodes(std::span<const std::int64_t> ids, std::vector<std::int32_t>& out);
  /// The mesh node of node id `id` (any node of the part), -1 if the part has none.
  std::int32_t mesh_node_of(std::int64_t id) const;
  /// Whether this rank owns a mesh or outside node (never an outside node), and its owner.
  bool owns(std::int32_t node) const {
    return node < disc_.mesh().n_nodes() && disc_.owns_node(node);
  }
  int owner_of(std::int32_t node) const;
  /// Reference coordinate c and id in the mesh as read of a mesh or outside node.
  double reference(std::int32_t node, int c) const;
  std::int64_t node_id(std::int32_t node) const;
  /// The current positions (reference plus u_mesh_) of `nodes` (mesh or outside nodes).
  void node_positions(std::span<const std::int32_t> nodes, std::vector<double>& out) const;
  /// The mesh nodes whose displacement this rank's evaluation reads (sorted): per side the
  /// slave nodes of its owned slave elements and the slave nodes it owns (their normals are
  /// the only ones computed, set here), the nodes of the facets around them (the normals read
  /// them), the master nodes (surface nodes) of the facets it hands in to the search and of
  /// its ghosts, and with friction the nodes its part of M^n and D^n reaches. The same with
  /// energy-momentum contact (whose discrete gradient reads the start of the step at them
  /// too); with its friction also the rings of the slave rows of the rank's M^n and D^n.
  std::vector<std::int32_t> nodes_read();
  /// u_mesh_ at u for nodes_read() (and u_mesh_start_ at the start of the step for the same
  /// nodes): the scatter is made anew when the nodes changed on some rank (one Allreduce to
  /// decide). Collective.
  void refresh_displacement(const la::Vector& u);
  /// The mesh node of a node id of the mesh as read (Discretization::node_gid) if it is an
  /// interface node, else -1.
  std::int32_t node_of_gid(std::int64_t number) const;

  /// With a modified slave basis the slave rows are combined by T^T first (P, identity on
  /// every other row): T^T r_S + D lambda, in which each multiplier stands alone.
  bool transformed() const;
  /// dP = P - I at the current active set and multipliers (nonzero on the slave rows of the
  /// contact zone only).
  la::Matrix transformation_delta() const;

  /// Side s placed at the interface displacement u and time t, with its candidate pairs (the
  /// distributed search, or the interface's own). Collective.
  void search(Side& s, std::span<const double> u, double t);
  /// The first distribution of side s (at its first evaluation, when its candidate pairs are
  /// known), or a redistribution with the current pairs.
  void distribute(Side& s);
  /// This rank evaluates the slave facets `ids` (global ids) of side s from now on (with the
  /// slave side held in part, hold_slave_part(s, ids, kept, false) first). Collective.
  void evaluate_facets(Side& s, std::vector<std::int64_t> ids, std::vector<std::int64_t> kept);
  /// The cut of the independent distribution of side k in the restart checkpoint, if it was
  /// made on as many ranks: the trees restored into s.distribution, and the ids of the slave
  /// facets this rank evaluated (its own part file). Otherwise none, and the first evaluation
  /// cuts anew. Either way a line of `notes` says which. Collective.
  std::optional<std::vector<std::int64_t>> read_cut(const Checkpoints& checkpoints, Side& s,
                                                    std::size_t k, std::vector<std::string>& notes);
  /// A slave side held in part with the independent distribution: after a distribution that
  /// gives this rank the slave facets `evaluated` (global ids), the side holds the rings of
  /// the slave nodes it owns (it decides their status from their normals) and of the nodes of
  /// the evaluated facets (the averaged normals, the output rows), with friction also of the
  /// slave nodes of its parts of M^n and M (its slip sums until the next save); the nodal
  /// arrays (friction's included) follow by node id (the owners, who hold their nodes before
  /// and after, publish their values to the new holders), M^n and M by slave node.
  /// Collective.
  /// Always also the rings of the slave nodes of this rank's part of M^n and of `kept` (ids).
  /// `own_cells` (a restart, before the first distribution: `kept` the slave nodes of the
  /// part of M^n read): the facets of its own and ghost cells instead of the owned nodes'
  /// rings.
  void hold_slave_part(Side& s, std::vector<std::int64_t> evaluated, std::vector<std::int64_t> kept,
                       bool own_cells);
  /// The node ids, owners and holder publication of the slave nodes `s` holds, and the ids
  /// (`facet_ids`, those of its facets), own facets and search ids of its slave side (after the
  /// side changed).
  void index_slave_side(Side& s, std::vector<std::int64_t> facet_ids);
  /// The slave facets of ids `ids` (sorted, unique) as a side: nodes in increasing id, each a
  /// mesh node or an outside node (map_nodes), with reference coordinates. Collective.
  meshtying::InterfaceSide slave_side_of(std::span<const SlaveFacet> facets);
  /// The directories of the outside nodes and of the slave facets, made once (collective).
  void make_directories();
  /// How many of the slave facets `ids` (global ids, sorted, unique) of side s, a slave side
  /// held in part with the independent distribution, are not in the side: asked of the facet
  /// directory. Collective.
  std::size_t count_outside_side(Side& s, std::vector<std::int64_t> ids);
  /// A two-body interface whose sides share nodes: the same InputError on every rank (the
  /// nodes counted by their owners). Collective.
  void check_shared_nodes(const Side& s, const io::Interface& itf) const;
  /// interface_nodes_ from the sides' nodes.
  /// A slave side held in part against a rigid plane: the plane's facet and the search
  /// inflation agreed over the parts (those of the whole side). Collective.
  void agree_on_obstacle_search(Side& s) const;
  void collect_interface_nodes();

  const Discretization& disc_;
  io::ParallelConfig parallel_;
  std::vector<std::int32_t> interface_nodes_; ///< mesh nodes of all sides, sorted
  std::int64_t interface_total_ = 0;          ///< interface nodes of all ranks
  /// Their ids in the mesh as read (node_gid), sorted, with the mesh node of each.
  mutable std::vector<std::pair<std::int64_t, std::int32_t>> interface_numbers_;
  std::vector<std::int32_t> gathered_; ///< the nodes gather_ brings (nodes_read())
  la::Gather gather_;                  ///< their dofs, node-major
  bool gather_made_ = false;
  /// Displacement of the nodes read (dim per mesh node; stale elsewhere).
  std::vector<double> u_mesh_;
  /// Displacement at the start of the energy-momentum step (start_step), and the same for
  /// the nodes read (dim per mesh node; stale elsewhere), filled by the scatter of u_mesh_.
  la::Vector u_start_;
  bool has_start_ = false;  ///< start_step was called
  bool start_read_ = false; ///< u_mesh_start_ holds u_start_ at the nodes read
  std::vector<double> u_mesh_start_;
  std::vector<Side> sides_;
  /// Nodes outside this rank's part: master nodes of the ghosts (master sides held in part)
  /// and slave nodes of the facets sent to it (slave sides held in part, the independent
  /// distribution). Outside node k is node n_nodes + k of u_mesh_, of the slave side and of the
  /// mortar entries; kept once found.
  struct OutsideNode {
    std::int64_t id = 0;
    std::int64_t dofs[3] = {0, 0, 0};
    int owner = -1;
    double x[3] = {0, 0, 0}; ///< reference coordinates
  };
  std::vector<OutsideNode> outside_;
  /// Reference coordinates of the mesh nodes, then of the outside nodes (dim per node): what
  /// the interfaces' gap blocks read (ContactInterface::set_reference_coordinates).
  std::vector<double> reference_x_;
  std::vector<std::pair<std::int64_t, std::int32_t>> outside_index_; ///< (id, node), sorted
  std::vector<OutsideNode> directory_; ///< this rank's part of the directory, sorted by id
  bool directory_made_ = false;
  la::Matrix Kc_, dP_;
  bool saddle_point_ = false;
  bool energy_momentum_ = false;      ///< integrator: energy_momentum
  bool held_ = false;                 ///< hold_sets
  int released_ = 0;                  ///< n_released()
  std::int64_t folded_node_ = -1;     ///< folded_node()
  bool evaluated_ = false;            ///< evaluate() ran before (the run has started)
  double last_solve_residual_ = -1.0; ///< last_solve_residual()
  PetscInt n_lm_ = 0;                 ///< multipliers this rank owns (those of its slave nodes)
  PetscInt first_lm_ = 0;             ///< global index of the first of them
  bool lm_numbered_ = false;          ///< the sides' multiplier rows are numbered
};

} // namespace seam::problem
