#pragma once
// The monolithic fluid-structure system with the fluid-split dual-mortar condensation
// (Kloeppel, Popp, Kuettler & Wall 2011; docs/fsi.md). Raw fields on the nodes of the mesh:
// the structure displacement d on the nodes of solid cells, the fluid velocity and pressure
// (u, p) and the fluid mesh displacement m on the nodes of fluid cells. The condensed unknowns
// x are what is left after eliminating
//   - prescribed values (structure `dirichlet`, fluid `velocity`): known, g(t);
//   - the fluid interface velocity: u_G = P v_G, v the structure velocity of its
//     generalized-alpha step, a function of d_{n+1} (steady: the structure rests, u_G = 0);
//   - the fluid interface mesh displacement: m_G = P d_G, P = D^-1 M (dual mortar, fluid side
//     slave, structure master, integrated once on the reference interface);
//   - the mesh displacement of the other fluid boundary nodes: held at 0 (on the facets of a
//     slip wall, a `velocity` condition on some components, only in those: the mesh slides).
// So raw = T_c x + g. The residual rows are gathered by another map R: the fluid momentum
// rows of interface nodes go to the structure's rows through P^T (force and energy
// conserving), the mesh rows of interface nodes and all rows of prescribed dofs are dropped.
// The Newton system is R^T J T_c dx = -R^T r with every block of J: the solid tangent, the
// fluid by (u, p), the fluid by the mesh position and velocity (shape derivatives), the
// pseudo-elastic mesh stiffness, the mass blocks of a time step.
//
// The mesh is this rank's part of a distributed mesh (runs: its cells and a ghost layer) or
// the whole mesh on every rank (the unit tests; then the cells are partitioned by METIS and the
// nodes numbered as a fluid run's, mesh::number_nodes). Each rank assembles its cells. On a
// distributed mesh the couplings are those of the fluid nodes this rank holds, their P rows
// from the nodes' owners (meshtying::TiedInterface::projection); the structure nodes P reaches
// that the rank does not hold follow the mesh's nodes (node numbers n_mesh_nodes() on), known
// by their global numbers, their coordinates, and the numbers of their unknowns and their
// prescribed components from their owners. The condensed unknowns are numbered by the owners of
// their nodes: each rank's block holds its nodes' structure, then fluid, then mesh unknowns, after
// the blocks of the lower ranks. The raw residual of a rank's cells is summed on the owners of its
// nodes (one assembly of a node-laid-out vector), so that a Newton iteration needs the
// unknowns of the held nodes only (held_unknowns), never all (docs/fsi.md "In parallel").
#include "seam/common/mpi.hpp"
#include "seam/fluid/navier_stokes.hpp"
#include "seam/io/config.hpp"
#include "seam/la/petsc.hpp"
#include "seam/mesh/distribute.hpp"
#include "seam/meshtying/tied_interface.hpp"
#include "seam/solid/material.hpp"

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

namespace seam::problem {
struct CanonicalOrder;
} // namespace seam::problem

namespace seam::fsi {

/// A sparse map from raw dofs to condensed indices: per raw dof a list of (index, weight).
struct DofMap {
  std::vector<std::int64_t> offsets{0};
  std::vector<PetscInt> index;
  std::vector<double> weight;
  void append_row() { offsets.push_back(static_cast<std::int64_t>(index.size())); }
  void add(PetscInt i, double w) {
    index.push_back(i);
    weight.push_back(w);
  }
};

/// P = D^-1 M of one interface: per fluid interface node its structure nodes and weights.
/// Distributed: the fluid nodes this rank holds (their rows complete for the nodes of its
/// cells), the structure nodes possibly beyond the mesh's (FsiSystem::n_mesh_nodes()).
struct FsiCoupling {
  std::string name;
  std::vector<std::int32_t> fluid_nodes; ///< mesh nodes, sorted
  std::vector<std::int64_t> offsets{0};
  std::vector<std::int32_t> structure_nodes;
  std::vector<double> weights;
  double d_total = 0.0;           ///< sum of D_jj over all ranks (the interface's length or area)
  std::vector<double> d_diagonal; ///< D_jj per fluid interface node
};

class FsiSystem {
public:
  /// Checks the input for a steady fsi run (InputError, located, on every rank) and builds
  /// the maps. `part` (kept by reference): `mesh` is this rank's part of a distributed mesh
  /// (part->mesh, `interfaces` set up on it distributed, with their `projection`); null: the
  /// mesh is replicated (`interfaces` set up whole).
  FsiSystem(const io::Config& config, const mesh::Mesh& mesh,
            const std::vector<meshtying::TiedInterface>& interfaces, Comm comm,
            const mesh::DistributedMesh* part = nullptr);

  int dim() const { return dim_; }
  Comm comm() const { return comm_; }
  const mesh::Mesh& mesh() const { return *mesh_; }
  PetscInt n_unknowns() const { return n_unknowns_; }
  PetscInt n_owned() const { return n_owned_; }
  PetscInt first_owned() const { return first_owned_; }
  /// The condensed unknowns this rank's cells need (the columns of their raw dofs, through
  /// P the structure nodes of their interface nodes) and those of the interface nodes (held
  /// whole), ascending: what a Newton iteration scatters to this rank.
  const std::vector<PetscInt>& held_unknowns() const { return held_; }
  /// The mesh's nodes; the nodes from there to n_nodes() are structure nodes of the couplings
  /// this rank does not hold.
  std::size_t n_mesh_nodes() const { return static_cast<std::size_t>(mesh_->n_nodes()); }
  std::size_t n_nodes() const { return n_nodes_; }
  /// The reference coordinates of node n.
  const double* node_x(std::size_t n) const {
    return n < n_mesh_nodes() ? &mesh_->x[n * dim_] : &extra_x_[(n - n_mesh_nodes()) * dim_];
  }
  /// Node n's id in the mesh as read (the same on every rank).
  std::int64_t node_gid(std::int32_t n) const { return part_ ? node_gid_[n] : n; }
  /// Whether this rank owns mesh node n (its raw residual entries are summed here).
  bool owns_node(std::int32_t n) const { return node_owner_[n] == comm_.rank(); }
  /// Whether this rank owns the node of raw dof a.
  bool owns_raw(std::size_t a) const { return owns_node(raw_node(a)); }
  std::int32_t raw_node(std::size_t a) const {
    return static_cast<std::int32_t>(a < base_f_   ? a / dim_
                                     : a < base_m_ ? (a - base_f_) / (dim_ + 1)
                                                   : (a - base_m_) / dim_);
  }
  /// A number of raw dof a that is the same on every rank and for any number of ranks.
  std::int64_t raw_id(std::size_t a) const {
    const auto n = raw_node(a);
    return node_gid(n) * static_cast<std::int64_t>(raw_slots()) +
           static_cast<std::int64_t>(raw_slot(a));
  }
  const mesh::DistributedMesh* part() const { return part_; }
  /// The cells this rank assembles.
  const std::vector<std::int32_t>& local_cells() const { return local_cells_; }
  /// Raw nodal vectors (checkpoints): 3 dim + 1 slots per node (d, then u and p, then m), the
  /// owned nodes' slots owned, the other held nodes' slots ghosts. Their stored order is by
  /// global node id (raw_id), independent of the number of ranks.
  la::Vector make_raw_vector() const;
  problem::CanonicalOrder raw_order() const;
  /// Raw values (n_raw) into such a vector (owned and ghost entries) and back.
  void raw_to_vector(std::span<const double> raw, la::Vector& v) const;
  void vector_to_raw(const la::Vector& v, std::vector<double>& raw) const;
  /// The held unknowns (x as in expand) from a raw state: the raw value of each one's raw dof.
  void unknowns_from_raw(std::span<const double> raw, std::vector<double>& x) const;
  std::size_t n_raw() const { return static_cast<std::size_t>(base_m_) + n_nodes_ * dim_; }

  /// Raw dof numbers: d of node n component i, u (c < dim) or p (c = dim), m.
  std::size_t d_dof(std::int32_t n, int i) const { return static_cast<std::size_t>(n) * dim_ + i; }
  std::size_t f_dof(std::int32_t n, int c) const {
    return base_f_ + static_cast<std::size_t>(n) * (dim_ + 1) + c;
  }
  std::size_t m_dof(std::int32_t n, int i) const {
    return base_m_ + static_cast<std::size_t>(n) * dim_ + i;
  }
  bool is_solid_node(std::int32_t n) const { return solid_node_[n] != 0; }
  bool is_fluid_node(std::int32_t n) const { return fluid_node_[n] != 0; }
  bool has_pressure(std::int32_t n) const { return pressure_node_[n] != 0; }
  bool is_fluid_cell(std::int32_t c) const { return cell_fluid_[c] >= 0; }
  const std::vector<FsiCoupling>& couplings() const { return couplings_; }
  /// The owned condensed unknowns of each field (global numbers): the structure d, the fluid
  /// (u, p) and the fluid mesh m, numbered in three consecutive ranges (the fieldsplit
  /// preconditioner of `linear: iterative`, docs/fsi.md "Linear solvers").
  void owned_fields(std::vector<PetscInt>& structure, std::vector<PetscInt>& fluid,
                    std::vector<PetscInt>& mesh) const;
  /// The rigid-body modes (3 in 2D, 6 in 3D: translations, rotations about the origin) on
  /// the owned structure unknowns of owned_fields, mode-major: the near-null space of the
  /// structure block for GAMG. Built here rather than by MatNullSpaceCreateRigidBody
  /// (la::Matrix::set_near_null_space), which needs every node's dim unknowns in one block:
  /// the structure block leaves out prescribed components, so a node may hold fewer.
  std::vector<double> structure_rigid_modes() const;
  /// Whether every fluid cell is a Taylor-Hood cell (no stabilized equal-order cells).
  bool taylor_hood() const { return taylor_hood_; }
  /// Whether raw dof a holds a prescribed value (a `velocity` or `dirichlet` condition).
  bool is_prescribed(std::size_t a) const { return prescribed_[a] >= 0; }

  /// Time integration (docs/fsi.md, "Dynamics"): the structure by generalized-alpha (Chung &
  /// Hulbert 1993), the fluid and its mesh by generalized-alpha for first-order systems
  /// (Jansen, Whiting & Hulbert 2000), with one rho_inf, so that both fields' residuals are
  /// taken at the same time t_n + dt / (1 + rho_inf). The state at t_n: raw values `old`, and
  /// `rate` (v on d dofs, du/dt on u dofs, dm/dt on m dofs) and `accel` (a on d dofs).
  struct History {
    double dt = 0.0;
    double s_am = 0.0, s_af = 0.0, beta = 0.25, s_gamma = 0.5; ///< structure
    double f_am = 1.0, f_af = 1.0, f_gamma = 1.0;              ///< fluid and mesh
    std::vector<double> old, rate, accel;
    static History from_rho_inf(double rho_inf, double dt, std::size_t n_raw);
  };
  /// With `h` (kept by reference) the system is the step t_n -> t_n + h->dt; null: steady.
  void set_history(const History* h) { history_ = h; }
  /// The rate and acceleration at t_{n+1} of the raw state of a step (History's recursions).
  void rates(std::span<const double> raw, std::vector<double>& rate,
             std::vector<double>& accel) const;
  /// The raw values of the prescribed part g(t) (zero elsewhere).
  std::vector<double> prescribed(double t) const;
  /// raw = T_c x + g, x the values of held_unknowns() (in that order), in the raw dofs whose
  /// unknowns are all held (the nodes of this rank's cells and of the interfaces); g in the
  /// others.
  void expand(std::span<const double> x, std::span<const double> g, std::vector<double>& raw) const;
  /// The position of unknown k in held_unknowns(), or -1.
  std::ptrdiff_t held_position(PetscInt k) const {
    const auto it = std::lower_bound(held_.begin(), held_.end(), k);
    return it != held_.end() && *it == k ? it - held_.begin() : -1;
  }

  struct Options {
    bool shape_derivatives = true; ///< false: drop d r_fluid / d m (tests show it matters)
  };
  struct Result {
    bool inverted = false;
    double strain_energy = 0.0;  ///< of the structure at t_{n+1}, all ranks
    double kinetic_energy = 0.0; ///< of the structure at t_{n+1} (1/2 v M v), all ranks
    /// The force level: the norm over the condensed rows of the sums of the magnitudes of the
    /// element contributions (round-off in the residual is a small multiple of eps times this).
    double level = 0.0;
    /// The raw residual r = f_int - f_ext (reactions on prescribed dofs, the fluid's interface
    /// forces before the transfer): summed over ranks in the raw dofs of the nodes this rank
    /// owns, 0 in all others (a sum over nodes is a sum of the ranks' partial sums).
    std::vector<double> raw_residual;
    /// Wall time of this call on this rank: the element kernels (assembly) and the products
    /// with R and T_c into the condensed matrix (condensation).
    double assembly_seconds = 0.0, condensation_seconds = 0.0;
  };
  /// The condensed residual R^T r (a vector of n_owned entries per rank, made here) and, if
  /// J is given, the condensed Jacobian R^T J T_c, both assembled. Collective.
  /// The Jacobian's pattern does not depend on the state (entries that happen to be zero are
  /// kept): a J that this system made in an earlier call with the same options only gets new
  /// values, in place, so that MUMPS reuses its symbolic analysis; an empty J is made.
  Result assemble(std::span<const double> raw, double t, la::Vector& r, la::Matrix* J,
                  const Options& options) const;

  /// The fluid's energy integrals (fluid::energy_integrals) over all fluid cells, summed over
  /// ranks, at the raw state `raw` on its mesh X + m, with the mesh velocity from `rate` (the
  /// rates of the state, empty: w = 0). Collective.
  fluid::EnergyIntegrals fluid_energy(std::span<const double> raw,
                                      std::span<const double> rate) const;

  /// Per node (width values each, node-major, n_nodes()): the sums over the ranks holding the
  /// node of their `contributions`, on every rank holding it (distributed mesh). Collective.
  std::vector<double> share(std::span<const double> contributions, int width) const;

private:
  /// Adds R^T K T_c of one element block to the triplets; I and J null: the values only.
  void add_block(std::span<const std::size_t> rows, std::span<const std::size_t> cols,
                 std::span<const double> K, std::vector<PetscInt>* I, std::vector<PetscInt>* J,
                 std::vector<double>& V) const;

  /// A vector of `width` values per node laid out as share's (owned nodes, then ghost_nodes_).
  la::Vector nodal_vector(int width) const;
  /// The local index of value k of node n in such a vector, whose first owned row is `first`.
  std::size_t nodal_local(std::int32_t n, std::size_t k, PetscInt first, std::size_t width) const;

  const io::Config* config_;
  const mesh::Mesh* mesh_;
  const mesh::DistributedMesh* part_ = nullptr;
  Comm comm_;
  int dim_;
  std::size_t n_nodes_ = 0, base_f_ = 0, base_m_ = 0;
  solid::PlaneMode plane_ = solid::PlaneMode::none;
  std::vector<int> cell_fluid_;    ///< index into fluids_, or -1
  std::vector<int> cell_solid_;    ///< index into solids_, or -1
  std::vector<double> mesh_young_; ///< per cell: the pseudo-elastic modulus (fluid cells)
  std::vector<fluid::Fluid> fluids_;
  std::vector<solid::Material> solids_;
  std::vector<char> solid_node_, fluid_node_, pressure_node_;
  std::vector<std::int32_t> local_cells_;
  std::vector<std::int64_t> node_gid_; ///< distributed: per node its id in the mesh as read
  std::vector<double> extra_x_;        ///< the coordinates of the nodes after the mesh's
  std::vector<int> node_owner_;
  /// The node-laid-out vector the raw residual is summed in: node n's slots from
  /// node_slot_[n] * raw_slots(), each rank's owned nodes one contiguous range.
  std::vector<std::int64_t> node_slot_;
  std::int64_t n_owned_nodes_ = 0;
  std::vector<std::int32_t> held_nodes_; ///< the nodes of local_cells_, ascending
  std::vector<PetscInt> held_;
  std::vector<PetscInt> own_; ///< per raw dof: its unknown (raw = x there), or -1
  /// Per entry of T_c (columns_): the position of its unknown in held_, or -1.
  std::vector<std::ptrdiff_t> held_column_;
  /// The ghosts of the raw nodal vectors: the held nodes this rank does not own, in node order.
  std::vector<std::int32_t> ghost_nodes_;
  std::size_t raw_slots() const { return static_cast<std::size_t>(3 * dim_ + 1); }
  /// The slot of raw dof a within its node's raw_slots().
  std::size_t raw_slot(std::size_t a) const {
    return a < base_f_   ? a % dim_
           : a < base_m_ ? dim_ + (a - base_f_) % (dim_ + 1)
                         : 2 * dim_ + 1 + (a - base_m_) % dim_;
  }
  std::vector<FsiCoupling> couplings_;
  /// Per raw dof: the expression of a prescribed value (-1: none).
  std::vector<int> prescribed_;
  std::vector<io::Expression> values_;
  DofMap columns_; ///< T_c
  /// Per raw dof: 1 for the interface velocity u_G = P v(d), whose T_c weights are P and get
  /// the factor dv/dd = gamma / (beta dt) (0 when steady: u_G = 0).
  std::vector<char> velocity_row_;
  const History* history_ = nullptr;
  double column_scale(std::size_t a) const {
    return velocity_row_[a] == 0 ? 1.0
           : history_            ? history_->s_gamma / (history_->beta * history_->dt)
                                 : 0.0;
  }
  DofMap rows_; ///< R
  PetscInt n_unknowns_ = 0, n_owned_ = 0, first_owned_ = 0;
  PetscInt end_structure_ = 0, end_fluid_ = 0; ///< the fields' ends in this rank's block
  std::vector<std::size_t> structure_raw_;     ///< the raw d dof of each owned structure unknown
  bool taylor_hood_ = true;
  /// The last Jacobian made from triplets: its handle, the options it was made with and its
  /// triplet count (assemble then sets only its values).
  mutable Mat pattern_of_ = nullptr;
  mutable bool pattern_shape_ = true;
  mutable std::size_t pattern_size_ = 0;
};

} // namespace seam::fsi
