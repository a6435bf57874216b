#pragma once
// One mortar contact interface in the current configuration (seed paper Sect. 2 and 4.2;
// ALGORITHMS.md §5): the slave side of the mesh against a master side of the mesh or a rigid
// plane, the k-DOP search refitted to the current positions, and per slave node j the mortar
// quantities of frictionless contact,
//   D_jj,   g~_j = int Phi_j g dA,   n_j (averaged nodal normal),
// the contact force of given normal multipliers lambda_n (slave node j: D_jj lambda_n,j n_j,
// master node l: -sum_j M_jl lambda_n,j n_j) and its exact derivatives together with those of
// the weighted gaps (mortar::linearize_slave_facet: normals, projections, clip polygons,
// integration cells, dual coefficients, D, M and g~).
//
// No PETSc and no MPI: a caller that distributes the work gives each rank its slave facets
// (set_owned_facets; all of them by default), evaluates them there and sums the partial
// results; the indices it gets are mesh dofs, node * dim + component.
//
// A rigid obstacle (rigid_obstacle.hpp: plane, sphere or cylinder) is an analytic surface moved
// by the prescribed motion; it has no dofs, so no derivative with respect to it is kept. Each
// candidate slave facet is integrated as a whole against it (rigid_obstacle_facet.hpp) instead
// of being clipped against master facets, and the contact normal of slave node j is the
// obstacle's normal at the node's closest point: constant for a plane, -(x_j - c) / |x_j - c|
// for a sphere, whose derivative enters the tangent. A plane is also a single master facet
// (line2 / quad4) far larger than the slave surface, for the k-DOP search; the candidates of a
// round obstacle are the slave facets within the search inflation of its surface.
#include "seam/contact/rigid_obstacle_facet.hpp"
#include "seam/contact/self_contact.hpp"
#include "seam/io/config.hpp"
#include "seam/mesh/mesh.hpp"
#include "seam/meshtying/interface_side.hpp"
#include "seam/mortar/interface.hpp"
#include "seam/mortar/linearization.hpp"
#include "seam/search/interface_search.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace seam::contact {

/// A matrix entry over mesh dofs (row and column: node * dim + component).
struct DofTriplet {
  std::int64_t row = 0;
  std::int64_t col = 0;
  double value = 0.0;
};

/// An entry of M: slave node j (side-local), master mesh node, value.
struct MortarEntry {
  local_index slave = 0;
  std::int32_t master_node = 0;
  double value = 0.0;
};

/// One part's share of the nodal mortar quantities (sum the shares of all parts).
struct NodalValues {
  std::vector<double> D;   ///< D_jj per slave node
  std::vector<double> gap; ///< g~_j per slave node
  std::vector<MortarEntry> M;
  /// Standard multipliers only: the entries D_jk, j != k (row j, column k side-local); the
  /// slave force of node k is sum_j D_jk lambda_n,j n_j.
  std::vector<mortar::Triplet> D_coupling;
  double area = 0.0; ///< integrated area (length in 2D) of the slave/master overlap
  /// Integration cells per slave facet (all facets; nonzero at this part's only).
  std::vector<local_index> facet_cells;
  local_index n_pairs = 0;
  local_index n_cells = 0;
};

/// One part's share of the linearization at fixed normal multipliers.
struct Linearization {
  /// d(contact force)/d(displacement) at fixed lambda_n: rows and columns mesh dofs.
  std::vector<DofTriplet> force_tangent;
  /// d g~_j / d(displacement) of the requested slave nodes: row = j (side-local), column =
  /// mesh dof.
  std::vector<DofTriplet> gap_gradient;
  /// Frictional interfaces, for the requested slave nodes: d D_jj / d(displacement) (row j) and
  /// the derivative of sum_l M_jl x_l - D_jj x~_j at fixed nodal positions x, i.e. of the
  /// operators only (row j * dim + component; x~ = T^-1 x with a modified slave basis); two
  /// bodies only.
  std::vector<DofTriplet> D_gradient;
  std::vector<DofTriplet> operator_gradient;
};

/// One candidate pair's contributions to the weighted gaps of its slave nodes, with their
/// first or second derivatives (energy-momentum contact, docs/contact_dynamics.md §4, §5). The
/// variables are the coordinates of the pair's slots: the slave facet's nodes, the master
/// facet's nodes and the other nodes of the facets that enter the slave nodes' averaged
/// normals; variable dim * slot + c is coordinate c of mesh dof dofs[slot] (dofs[slot] < 0:
/// unused slot).
struct GapBlock {
  int dim = 2;
  std::vector<local_index> slave; ///< side-local slave nodes of the rows
  std::vector<std::int64_t> dofs; ///< mesh dof of coordinate 0 of each slot
  std::vector<double> gap;        ///< contribution to g~_j, one per row
  std::vector<double> gradient;   ///< rows x n_variables (GapOrder::gradient and hessian)
  std::vector<double> hessian;    ///< rows x n_variables^2, row-major (GapOrder::hessian)
  int n_variables() const { return dim * static_cast<int>(dofs.size()); }
  /// The mesh dof of variable v, -1 for an unused slot.
  std::int64_t dof(int v) const {
    const auto slot = dofs[static_cast<std::size_t>(v / dim)];
    return slot < 0 ? std::int64_t{-1} : slot + v % dim;
  }
};
namespace detail {
/// Tests only: what the 3D gap Hessians leave out, to show that the Newton matrix needs it.
enum class GapHessianTerms { all, without_normal_curvature, none };
extern GapHessianTerms gap_hessian_terms;
/// Diagnostics: line2 pairs gap_blocks dropped by the centre-normal pre-check, for want of
/// an overlap, and of those with an unconverged projection (counted, never reset).
extern long gap_rejections[3];
} // namespace detail

/// What gap_blocks computes: values, first or second derivatives.
enum class GapOrder { value, gradient, hessian };

/// y = T^-1 x for the slave nodal vectors x (dim values per slave node) and the triplets of
/// T^-1 (side-local; mortar::inverse_transformation); nodes without a row keep their values.
/// With a modified slave basis (d = T d~) the positions that D multiplies in D x~_S = M x_M
/// are x~_S = T^-1 x_S (Popp et al. 2012).
void apply_inverse_transformation(std::span<const mortar::Triplet> T_inverse, int dim,
                                  std::span<const double> x, std::span<double> y);

/// The rows of T^-1 (side-local triplets, mortar::inverse_transformation) by slave node: with a
/// modified slave basis node k's position in it is x~_k = sum_m (T^-1)_km x_m, and the force
/// D_kk lambda_k on it acts on the nodes m by (T^-1)_km. A node without a row stands for itself.
class InverseTransformationRows {
public:
  InverseTransformationRows(std::span<const mortar::Triplet> T_inverse, std::size_t n_nodes);
  /// f(m, (T^-1)_km) for the entries of row k.
  template <class F> void visit(std::size_t k, F&& f) const {
    if (begin_[k] == begin_[k + 1]) {
      f(k, 1.0);
      return;
    }
    for (auto i = begin_[k]; i < begin_[k + 1]; ++i) f(col_[i], value_[i]);
  }

private:
  std::vector<std::size_t> begin_, col_;
  std::vector<double> value_;
};

class ContactInterface {
public:
  /// The sides of `config` (a `type: contact` interface) in `mesh` (kept by reference).
  /// Located InputError for regions that are missing or not boundaries, and for sides that
  /// share nodes.
  /// `slave_part`: the mesh holds part of the slave side (problem::slave_held_in_part), which
  /// may then be empty here; the caller checks the whole side and agrees the mesh size over
  /// the parts (set_slave_mesh_size).
  ContactInterface(const io::Interface& config, const mesh::Mesh& mesh, bool slave_part = false);
  ~ContactInterface();
  ContactInterface(ContactInterface&&) noexcept;
  ContactInterface& operator=(ContactInterface&&) noexcept;

  const std::string& name() const { return name_; }
  int dim() const { return slave_.dim; }
  const meshtying::InterfaceSide& slave() const { return slave_; }
  /// Mesh nodes of the master side (empty for a rigid plane).
  std::span<const std::int32_t> master_nodes() const;
  bool rigid() const { return rigid_; }
  /// The rigid obstacle in its current position (rigid() only).
  const Obstacle& obstacle() const { return current_; }
  /// Whether the rigid obstacle's prescribed displacement varies in time (rigid() only).
  bool obstacle_moves() const {
    return std::any_of(plane_motion_.begin(), plane_motion_.end(),
                       [](const io::Expression& e) { return e.uses_time(); });
  }
  /// Self and multi-body contact (`surface:`, self_contact.hpp): the slave and the master side
  /// are both the whole surface and every search assigns the roles of its facets.
  bool self_contact() const { return self_; }
  /// Contact with friction: multipliers are Cartesian vectors (dim per slave node) in
  /// add_force and linearize instead of normal multipliers.
  bool frictional() const { return frictional_; }
  /// The rigid obstacle's displacement at the last update (dim entries; zero for two bodies).
  /// Friction against it uses the slip increment relative to this translation.
  std::array<double, 3> plane_displacement() const;
  /// Current positions of the slave nodes (dim per slave node) and of the master nodes (dim
  /// per master node; the plane's corners for a rigid plane) at the last update.
  std::span<const double> slave_positions() const { return slave_.coordinates; }
  std::span<const double> master_positions() const { return master_.coordinates; }
  local_index n_master_facets() const { return master_.n_facets(); }
  /// Mean edge length of the slave facets in the reference configuration.
  double slave_mesh_size() const { return mesh_size_; }
  /// The sum and the number of the edge lengths of slave facets `facets` (reference
  /// configuration), and the mean edge length agreed over the parts of a slave side held in
  /// part (their sums over the facets each part evaluates).
  std::pair<double, double> slave_edge_sum(std::span<const local_index> facets) const;
  /// (Against a round obstacle the candidates' inflation follows it: 0.75 x the mean edge.)
  void set_slave_mesh_size(double size) {
    mesh_size_ = size;
    if (obstacle_.round()) search_options_.inflation = search_options_.inflation_factor * size;
  }
  /// A rigid plane: its one master facet spanned anew over the box lo..hi (dim entries; the
  /// whole slave side's box, so that every part of a slave side held in part searches against
  /// the same facet). The set-up spans it over the box of the slave facets the mesh holds.
  void span_plane(const std::array<double, 3>& lo, const std::array<double, 3>& hi);
  local_index n_slave_nodes() const { return static_cast<local_index>(slave_.mesh_nodes.size()); }

  /// Places both sides at the mesh displacement `u` (dim values per mesh node; only interface
  /// nodes are read) and the rigid plane at time t; refits the search trees and collects the
  /// candidate pairs; recomputes the averaged nodal normals. place() and the own search, or
  /// place() alone with an external search (use_external_search).
  void update(std::span<const double> u, double t);

  /// The current configuration without a search: both sides (and the obstacle) placed at `u`
  /// and t, the averaged nodal normals of a two-body or rigid interface recomputed. The
  /// candidate pairs are those of the last search until set_candidates() or update().
  void place(std::span<const double> u, double t);
  /// Two-body and self-contact interfaces: the candidate pairs come from outside (e.g. a search
  /// distributed over the ranks, problem/contact_search.hpp) through set_candidates() after
  /// each place(); the interface then keeps no search trees of its own. InputError on a rigid
  /// obstacle.
  void use_external_search();
  bool external_search() const { return external_; }
  /// Two bodies: the candidate pairs of the owned slave facets found outside (slave: side-local
  /// slave facet, master: side-local master facet), at the configuration of the last place();
  /// only facets that face each other are kept, as the own search keeps them. Self contact:
  /// the oriented pairs of the whole surface (self_contact.hpp: facing, roles assigned; the
  /// same on every part), of which the pairs of the owned slave facets are kept; the slave
  /// patch and the nodal normals are rebuilt from them.
  void set_candidates(std::span<const mortar::CandidatePair> pairs);
  /// With an external search, the master facets this part's mortar integration, linearization
  /// and gap blocks read: those the distributed search ghosted to it (parallel::SurfacePart
  /// layout; facet and node ids side-local, i.e. master facets and nodes of two bodies,
  /// surface facets and nodes of self contact; facet ids sorted; coordinates current, dim per
  /// node). Given before each set_candidates(); every master facet of an owned candidate pair
  /// must be among them (InputError otherwise). Without it the whole master side is read.
  /// With `mesh_nodes` (a master side held in part, problem/contact_search.hpp) the ghosts'
  /// nodes are given as mesh nodes instead (one per node; numbers at or beyond the mesh's
  /// node count name nodes outside this part, whose dofs the caller maps), `node_ids` are
  /// unused and refresh_master_coordinates() is not available.
  void set_master_facets(std::span<const std::int64_t> facet_ids,
                         std::span<const local_index> offsets,
                         std::span<const local_index> connectivity,
                         std::span<const std::int64_t> node_ids, std::span<const double> coords,
                         std::span<const std::int32_t> mesh_nodes = {});
  /// The quadrature degree of the integration cells (8 when a side has curved facets), and its
  /// replacement (a master side held in part: the degree all parts agree on).
  int cell_quadrature_degree() const { return options_.pair.cell_quadrature_degree; }
  void set_cell_quadrature_degree(int degree) { options_.pair.cell_quadrature_degree = degree; }
  /// The ghosted master facets' coordinates taken anew from the sides placed at the current
  /// state (place()), for an iteration that keeps the candidate pairs of an earlier search
  /// instead of searching (the search hands the ghosts with their coordinates).
  void refresh_master_coordinates();
  /// The same for ghosts given with `mesh_nodes`: their current coordinates from the caller
  /// (dim per ghost node, in their order).
  void set_master_coordinates(std::span<const double> coords);
  /// The master facets the integration reads as a side (the ghosted ones in their order, or
  /// the whole master side).
  const meshtying::InterfaceSide& master_read() const { return integration_master(); }
  /// Master facets and nodes the integration reads (the ghosted ones, or the whole side).
  local_index n_master_facets_read() const { return integration_master().n_facets(); }
  local_index n_master_nodes_read() const {
    return static_cast<local_index>(integration_master().mesh_nodes.size());
  }
  /// The absolute inflation of the search volumes (the same on every part).
  double search_inflation() const { return search_options_.inflation; }
  /// The inflation from the shortest edge of both sides, `min_edge` (a master side held in
  /// part: the shortest edge of all parts, so that every part searches as the whole does).
  void set_search_edge(double min_edge) {
    search_options_.inflation = search_options_.inflation_factor * min_edge;
  }
  /// The master side at the last update / place() (empty for a rigid obstacle).
  const meshtying::InterfaceSide& master() const { return master_; }

  /// The nodal transformation d = T d~ of a modified slave basis (dual multipliers on tri6 /
  /// quad8 facets; mortar::MortarOperators::T), side-local; empty when T = I. D, M and g~
  /// then refer to the modified basis and the slave contact force is T^-T (D lambda n).
  const std::vector<mortar::Triplet>& transformation() const { return transformation_; }
  /// T^-1 of transformation() (side-local; empty when T = I).
  const std::vector<mortar::Triplet>& transformation_inverse() const {
    return transformation_inverse_;
  }

  /// The current slave positions in the modified basis, x~ = T^-1 x (dim per slave node;
  /// x itself when T = I): the objective slip increment is built from them.
  std::vector<double> transformed_slave_positions() const;

  /// Averaged unit nodal normals of the slave side at the last update (dim per slave node):
  /// those of the nodes set_normal_nodes() asked for, zero at the others.
  const std::vector<double>& normals() const { return normals_; }
  /// The slave nodes whose averaged normals place() (and set_candidates() on self contact)
  /// computes: side-local, sorted; every node by default. Their normals read the positions
  /// of normal_ring(nodes) only.
  void set_normal_nodes(std::vector<local_index> nodes);
  /// Takes the nonzero normals of `normals` (dim per slave node, e.g. published by the nodes'
  /// owners, which computed them from the same facets) for the nodes whose normal this part
  /// did not compute; the others keep theirs.
  void set_normals_from_owners(std::span<const double> normals);
  /// Replaces the nodal normals (dim per slave node), e.g. by those kept through a change of
  /// the held slave facets that set_candidates() averaged anew over the side's reference
  /// coordinates.
  void set_normals(std::span<const double> normals) {
    SEAM_ASSERT(normals.size() == normals_.size());
    normals_.assign(normals.begin(), normals.end());
  }
  /// The slave nodes whose normals place() computes.
  local_index n_normals_computed() const {
    return all_normals_ ? n_slave_nodes() : static_cast<local_index>(normal_nodes_.size());
  }
  /// The slave nodes of the facets around `nodes` (side-local, sorted, `nodes` included): the
  /// positions their averaged normals read.
  std::vector<local_index> normal_ring(std::span<const local_index> nodes) const;
  /// The averaged normals of the slave nodes `nodes` (side-local, sorted; zero at the others)
  /// at the mesh displacement `u` (dim values per mesh node, read at normal_ring(nodes) only),
  /// with the slave patch and the obstacle of the last update, bit for bit those of the whole
  /// computation; the state is not changed (for the output rows a rank computes).
  std::vector<double> normals_at(std::span<const double> u,
                                 std::span<const local_index> nodes) const;
  /// The mesh node of the first slave node at which the normals of the slave facets cancel at
  /// the mesh displacement `u` (the surface folds back onto itself there), -1 if there is none
  /// or the slave faces a rigid obstacle (whose normals it uses). All slave facets held are
  /// summed; the state is not changed.
  std::int32_t folded_slave_node(std::span<const double> u) const;
  /// Standard (not dual) multipliers: D is not diagonal.
  bool standard() const { return options_.multiplier == mortar::Multiplier::standard; }
  /// Candidate pairs of the owned slave facets at the last update (after the facing test).
  local_index n_candidates() const { return static_cast<local_index>(pairs_.size()); }

  /// 2D, two bodies and self contact: the centre-normal pre-check of a pair (n_s . n_m below
  /// PairOptions::max_normal_alignment_2d, the facets' chords more than 95.7 degrees apart) is
  /// decided once per step attempt. keep_prechecked_pairs() takes the candidate pairs of the
  /// owned slave facets that pass it at the last update (or place() and set_candidates());
  /// from then on until forget_prechecked_pairs() they are integrated without it (evaluate,
  /// linearize, gap_blocks), wherever their facets turn. A pair then leaves the integration
  /// at most once in a step attempt, never back and forth between Newton iterates: a pair
  /// whose facets' angle sat at the threshold made the weighted gaps jump between the
  /// iterates of a period-2 cycle (examples/rings, 200 rings at t = 0.77;
  /// docs/contact_dynamics.md, "Pre-check kept within a step").
  void keep_prechecked_pairs();
  void forget_prechecked_pairs();
  /// The pairs (side-local slave facet, master facet) kept so far in the step attempt.
  std::span<const std::pair<local_index, local_index>> prechecked_pairs() const {
    return prechecked_;
  }

  /// The slave facets evaluate() and linearize() integrate (sorted, unique; all by default).
  void set_owned_facets(std::vector<local_index> facets);
  /// Two bodies, a rigid obstacle or a self-contact surface, a slave side held in part: the
  /// slave side (the surface, both sides, of self contact) becomes the facets
  /// of `region` (a subset of the slave region's facets in the mesh, in its order), the side-local
  /// indices those of `region`. The candidate pairs, the owned facets and the normal nodes are
  /// dropped (set anew by the caller); the normals of the nodes held before and after, the
  /// mesh size, the search inflation, the quadrature degree and a rigid plane's facet are
  /// kept.
  void hold_slave_facets(const mesh::Region& region);
  /// The same with the facets given as a side: `side.coordinates` are the reference
  /// coordinates of its nodes and `side.mesh_nodes` need not be sorted nor nodes of the mesh
  /// (numbers at or beyond the mesh's node count name nodes outside this part, as in
  /// set_master_facets; the displacement place() reads is indexed by them alike).
  void hold_slave_facets(meshtying::InterfaceSide side);
  std::span<const local_index> owned_facets() const { return owned_; }
  /// Candidate pairs of slave facet f at the last update.
  local_index n_pairs_of(local_index f) const {
    return pair_offsets_[static_cast<std::size_t>(f) + 1] -
           pair_offsets_[static_cast<std::size_t>(f)];
  }
  /// Candidate pairs of slave facet f at the last update.
  std::span<const mortar::CandidatePair> pairs_of(local_index f) const {
    return std::span<const mortar::CandidatePair>(pairs_).subspan(
        static_cast<std::size_t>(pair_offsets_[static_cast<std::size_t>(f)]),
        static_cast<std::size_t>(n_pairs_of(f)));
  }
  /// Centroid of slave facet f (its nodes' mean) at the last update, dim values.
  std::array<double, 3> slave_centroid(local_index f) const;

  /// D_jj, g~_j and M over the owned slave facets.
  void evaluate(NodalValues& out) const;

  /// This part's contact force of the normal multipliers `lambda_n` (one per slave node; on a
  /// frictional interface the Cartesian multipliers, dim per slave node) added to `force`
  /// (mesh dofs), from this part's `values`.
  void add_force(const NodalValues& values, std::span<const double> lambda_n,
                 std::span<double> force) const;

  /// The derivatives of this part's contact force at fixed `lambda_n` and of the weighted gaps
  /// of the slave nodes with `want_gap[j]` != 0. Only slave facets with a node that has a
  /// nonzero multiplier or a wanted gap are linearized.
  /// With `step_start` (the mesh displacement at the start of the step, dim per mesh node;
  /// two bodies, self contact and rigid obstacles) operator_gradient is instead the derivative
  /// of sum_k D_jk dx_k - sum_l M_jl dx_l at fixed dx = x - x_start (the slip increment of
  /// energy-momentum friction, problem/contact_energy_momentum_friction.cpp; no M against an
  /// obstacle). With a modified slave basis (transformation()) the slave positions and rows
  /// are then those of the modified basis: D_jj (T^-1 dx)_j, and the force D_jj lambda_j on
  /// node m by (T^-1)_jm.
  void linearize(std::span<const double> lambda_n, std::span<const char> want_gap,
                 Linearization& out, std::span<const double> step_start = {}) const;

  /// Whether gap_blocks is available: line2 or line3 facets (2D, one kind) or any surface facets
  /// (3D: tri3, quad4, tri6, quad8, quad9) on both sides, two bodies or self contact, or the
  /// slave side against a rigid plane, sphere or cylinder.
  bool has_gap_blocks() const;
  /// The weighted gaps g~_j as functions of the positions: each candidate pair of the owned
  /// slave facets of the last update (same pairs, slave patch and nodal normal averaging),
  /// evaluated at the mesh displacement `u` (dim values per mesh node; interface nodes read)
  /// with exact derivatives up to `order`. Summed over the blocks (and the parts), the values
  /// at the displacement of the last update are those of evaluate() to the projections'
  /// Newton tolerance. With GapOrder::hessian and a nonempty `hessian_rows` (one flag per
  /// slave node), a block none of whose slave nodes is flagged gets gradients only (an empty
  /// `hessian`): the Newton matrix needs the Hessians of the gaps with a nonzero multiplier.
  void gap_blocks(std::span<const double> u, GapOrder order, std::vector<GapBlock>& out,
                  std::span<const char> hessian_rows = {}) const;
  /// The reference coordinates gap_blocks and the energy-momentum linearization read (dim per
  /// node, numbered as the displacement they read): the mesh's nodes, then the nodes outside
  /// this part (sides held in part, problem::ContactConstraint); null: the mesh's. The vector
  /// is the caller's and must outlive the interface.
  void set_reference_coordinates(const std::vector<double>* x) { reference_x_ = x; }

  /// d n_j / d(displacement) of the averaged normal of slave node j at the last update: row =
  /// component, column = mesh dof, appended to `out`. Nothing for a rigid plane (its normal is
  /// fixed); for a round obstacle the derivative of its normal at the node.
  void normal_jacobian(local_index j, std::vector<DofTriplet>& out) const;

private:
  std::int64_t mesh_dof_of_master(local_index p) const; ///< -1 for rigid nodes
  /// gap_blocks of a 3D interface (gap_blocks_3d.cpp).
  void gap_blocks_3d(std::span<const double> u, GapOrder order, std::vector<GapBlock>& out,
                     std::span<const char> hessian_rows) const;
  /// Slave node j has a nonzero multiplier (normal or Cartesian, see frictional()).
  bool carries_multiplier(std::span<const double> lambda, local_index j) const;
  /// Component c of the multiplier vector of slave node j.
  double multiplier(std::span<const double> lambda, std::size_t j, int c) const;
  /// Rigid plane: D and g~ of slave facet f integrated over the whole facet, with their
  /// derivatives if asked (rigid_obstacle_facet.hpp).
  void rigid_facet(local_index f, bool derivatives, RigidObstacleFacet& out) const;
  /// Round obstacle: the candidate slave facets, those within the inflation of its surface.
  void collect_round_candidates();
  /// Appends to pairs_ those of `pairs` (owned slave facet, master facet) whose facets face
  /// each other (all of them against a rigid plane).
  void keep_facing(std::span<const mortar::CandidatePair> pairs);
  /// Self contact: appends to pairs_ those of `all` (the oriented pairs of the whole surface)
  /// of the owned slave facets; rebuilds the slave patch and the nodal normals.
  void take_self_pairs(std::span<const mortar::CandidatePair> all);
  /// pairs_ (of the owned slave facets) sorted, their offsets per slave facet.
  void index_pairs();
  /// options_.prechecked: the kept pairs among pairs_, in the indices of the facet sets
  /// integrated (slave_set(), integration_master()).
  void index_prechecked();
  void evaluate_rigid(NodalValues& out) const;
  /// T^-1 (x - x_ref - step_start) over the slave nodes (dim each); empty without step_start.
  std::vector<double> modified_increment(std::span<const double> step_start) const;
  void linearize_rigid(std::span<const double> lambda_n, std::span<const char> want_gap,
                       Linearization& out, std::span<const double> step_start) const;
  /// The slave facets the mortar integration and the nodal normals use: the whole slave side,
  /// or on a self-contact interface the current slave patch; facet f of the side is facet
  /// slave_index(f) of that set.
  mortar::FacetSet slave_set() const {
    return self_ ? patch_.facet_set(slave_) : slave_.facet_set();
  }
  const mortar::NodeFacets& slave_adjacency() const {
    return self_ ? patch_.adjacency : slave_adjacency_;
  }
  local_index slave_index(local_index f) const {
    return self_ ? patch_.index[static_cast<std::size_t>(f)] : f;
  }

  /// The master facets the integration reads: the ghosted ones (set_master_facets) or the
  /// whole master side; their mesh_nodes give the mesh node of each of their nodes.
  const meshtying::InterfaceSide& integration_master() const {
    return ghosted_ ? ghost_master_ : master_;
  }
  /// Side-local master facet f as a facet of integration_master().
  local_index integration_facet(local_index f) const;
  /// The mesh node of node p of integration_master().
  std::int32_t integration_node(local_index p) const {
    return integration_master().mesh_nodes[static_cast<std::size_t>(p)];
  }

  const mesh::Mesh* mesh_ = nullptr;
  std::string name_;
  bool rigid_ = false;
  bool frictional_ = false;
  bool self_ = false;
  bool external_ = false; ///< use_external_search
  meshtying::InterfaceSide slave_, master_;
  /// A slave side given by hold_slave_facets(side): its reference coordinates (dim per side
  /// node), read instead of the mesh's.
  std::vector<double> slave_reference_;
  const std::vector<double>* reference_x_ = nullptr; ///< set_reference_coordinates
  const std::vector<double>& reference_x() const { return reference_x_ ? *reference_x_ : mesh_->x; }
  /// `side` (slave_ or a copy) at the mesh displacement u (empty: the reference configuration).
  void place_slave(meshtying::InterfaceSide& side, std::span<const double> u) const;
  // The master facets ghosted to this part (set_master_facets): their side-local ids (sorted)
  // and, as a side, their nodes (mesh_nodes: the mesh node of each, not sorted) and current
  // coordinates.
  bool ghosted_ = false;
  std::vector<std::int64_t> ghost_ids_;
  meshtying::InterfaceSide ghost_master_;
  std::vector<std::int64_t> ghost_side_nodes_; ///< side-local id of each ghost_master_ node
  std::vector<std::int32_t> master_mesh_nodes_;
  // Rigid obstacle: its reference and current surfaces, the motion (a plane's reference corners
  // too) and the displacement at the last update.
  Obstacle obstacle_, current_;
  std::vector<double> plane_corners_;
  std::vector<io::Expression> plane_motion_;
  std::array<double, 3> obstacle_displacement_{};
  double mesh_size_ = 0.0;
  mortar::MortarOptions options_;
  mortar::NodeFacets slave_adjacency_;
  std::unique_ptr<search::InterfaceSearch> search_;
  std::unique_ptr<search::Tree> self_tree_;  ///< self contact: one tree over the surface
  SlavePatch patch_;                         ///< self contact: the current slave facets
  std::vector<mortar::CandidatePair> pairs_; ///< sorted by slave facet
  std::vector<local_index> pair_offsets_;    ///< per slave facet into pairs_
  /// keep_prechecked_pairs: side-local (slave facet, master facet), sorted.
  std::vector<std::pair<local_index, local_index>> prechecked_;
  std::vector<local_index> owned_; ///< slave facets this part evaluates
  // The search runs on the owned slave facets only (their offsets and nodes), with the
  // inflation of the whole interface so that every part finds the pairs a whole search would.
  std::vector<local_index> owned_offsets_, owned_nodes_;
  search::SearchOptions search_options_;
  std::vector<double> normals_;
  bool all_normals_ = true;               ///< set_normal_nodes not called
  std::vector<local_index> normal_nodes_; ///< set_normal_nodes
  /// The averaged normals of `side` (slave_ or a copy at other positions) at the nodes of
  /// set_normal_nodes(), or at every node.
  std::vector<double> averaged_normals(const meshtying::InterfaceSide& side, bool all) const {
    return averaged_normals(side, all, normal_nodes_);
  }
  /// At every node (`all`) or at `nodes` only.
  std::vector<double> averaged_normals(const meshtying::InterfaceSide& side, bool all,
                                       std::span<const local_index> nodes) const;
  std::vector<mortar::Triplet> transformation_;
  std::vector<mortar::Triplet> transformation_inverse_;
};

} // namespace seam::contact
