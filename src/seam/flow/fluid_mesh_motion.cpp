#include "seam/flow/fluid_mesh_motion.hpp"

#include "seam/ale/mesh_motion.hpp"
#include "seam/common/error.hpp"
#include "seam/mesh/cell_geometry.hpp"
#include "seam/mesh/facets.hpp"
#include "seam/problem/model.hpp"
#include "seam/solid/element.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace seam::flow {

using problem::Discretization;
using problem::find_region;

namespace {

// The Poisson ratio of the pseudo-elastic mesh: compressible enough to let cells change
// volume, stiff enough in shear to keep them from distorting.
constexpr double mesh_poisson = 0.3;

} // namespace

FluidMeshMotion::FluidMeshMotion(const io::Config& config, const FluidLayout& layout)
    : config_(config), layout_(layout) {
  const auto& mesh = layout.mesh();
  const int dim = mesh.dim;
  const std::int32_t n_nodes = mesh.n_nodes();
  // The motion of every cell: the index of its body if that body's mesh moves, else -1.
  std::vector<int> cell_body(mesh.n_cells(), -1);
  std::vector<std::int32_t> elastic_cells;
  for (std::size_t b = 0; b < config.bodies.size(); ++b) {
    const auto& body = config.bodies[b];
    if (!body.mesh_motion) continue;
    moving_ = true;
    for (auto c : find_region(mesh, body.region, {dim}, "a body").cells) {
      cell_body[c] = static_cast<int>(b);
      if (body.mesh_motion->model == io::MeshMotionModel::pseudo_elastic)
        elastic_cells.push_back(c);
    }
  }
  std::sort(elastic_cells.begin(), elastic_cells.end());
  elastic_.assign(n_nodes, 0);
  for (auto c : elastic_cells)
    for (auto n : mesh.cell(c)) elastic_[n] = 1;

  // Dirichlet data of the elastic solve: the mesh's boundary stays (zero), unless a condition
  // moves it; the nodes of cells that do not move elastically follow their body (or stay).
  source_.assign(n_nodes, Source{});
  const auto exterior = mesh::exterior_facets(mesh);
  for (std::int32_t f = 0; f < exterior.size(); ++f) {
    const auto cell = mesh.cell(exterior.cell[f]);
    for (int k : fem::facet_nodes(mesh.cell_type[exterior.cell[f]], exterior.local[f]))
      source_[cell[k]] = {Source::zero, -1};
  }
  for (std::size_t k = 0; k < config.boundary_conditions.size(); ++k) {
    const auto& bc = config.boundary_conditions[k];
    if (bc.type != io::BoundaryType::mesh_displacement) continue;
    const auto& region = find_region(mesh, bc.region, {0, 1, 2}, "a mesh displacement condition");
    // Owned nodes only (every cell around them is held): the same answer on every rank.
    bool outside = false;
    for (auto n : region.nodes) outside = outside || (layout.owns_node(n) && !elastic_[n]);
    if (layout.comm().any(outside))
      io::fail_at(bc.mark, "type 'mesh_displacement' drives the pseudo-elastic mesh of a fluid "
                           "body, but region '" +
                               bc.region.name +
                               "' has nodes outside every body with mesh_motion {model: "
                               "pseudo_elastic} (give such a body mesh_motion, or move a "
                               "prescribed body with its 'displacement')");
    for (auto n : region.nodes) source_[n] = {Source::condition, static_cast<int>(k)};
    moving_ = true;
  }
  for (std::int32_t c = 0; c < mesh.n_cells(); ++c) {
    const int b = cell_body[c];
    const bool elastic =
        b >= 0 && config.bodies[b].mesh_motion->model == io::MeshMotionModel::pseudo_elastic;
    if (elastic) continue;
    for (auto n : mesh.cell(c))
      source_[n] = b < 0 ? Source{Source::zero, -1} : Source{Source::body, b};
  }
  elastic_solve_ = layout.comm().any(!elastic_cells.empty()); // a part may hold none
  elastic_cells_ = std::move(elastic_cells);
  cell_body_ = std::move(cell_body);
}

FluidMeshMotion::~FluidMeshMotion() = default;

void FluidMeshMotion::build_solve() {
  const auto& mesh = layout_.mesh();
  const int dim = mesh.dim;
  const auto& elastic_cells = elastic_cells_;
  const auto& config = config_;
  // The stiffness of the pseudo-elastic mesh, once: E = (V_min / V_e)^chi per cell.
  disc_ = layout_.part() ? std::make_unique<Discretization>(*layout_.part(), layout_.comm())
                         : std::make_unique<Discretization>(mesh, layout_.comm());
  K_.emplace(disc_->make_matrix());
  std::vector<std::int32_t> local;
  for (auto c : disc_->local_cells())
    if (std::binary_search(elastic_cells.begin(), elastic_cells.end(), c)) local.push_back(c);
  // (V_min / V_e) with V_min over all elastic cells, to each body's power chi.
  double smallest = std::numeric_limits<double>::infinity();
  for (auto c : local) smallest = std::min(smallest, mesh::cell_volume(mesh, c));
  smallest = layout_.comm().min(smallest);
  const auto ratio = ale::jacobian_stiffening(mesh, elastic_cells, 1.0, smallest);
  const auto young = [&](std::int32_t c) {
    const auto& mm = *config.bodies[cell_body_[c]].mesh_motion;
    const double power = mm.stiffening == io::Stiffening::jacobian ? mm.stiffening_power : 0.0;
    const auto k =
        std::lower_bound(elastic_cells.begin(), elastic_cells.end(), c) - elastic_cells.begin();
    return std::pow(ratio[static_cast<std::size_t>(k)], power);
  };
  std::array<double, fem::max_cell_nodes * 3> X{}, zero{};
  std::array<PetscInt, fem::max_cell_nodes * 3> dofs{};
  std::vector<double> Ke;
  for (auto c : local) {
    const auto type = mesh.cell_type[c];
    const auto nodes = mesh.cell(c);
    const auto nd = nodes.size() * dim;
    for (std::size_t a = 0; a < nodes.size(); ++a)
      for (int i = 0; i < dim; ++i) {
        X[a * dim + i] = mesh.x[nodes[a] * dim + i];
        dofs[a * dim + i] = disc_->global_dof(nodes[a], i);
      }
    solid::ElementInput in;
    in.cell = type;
    in.dim = dim;
    in.plane = dim == 2 ? solid::PlaneMode::plane_strain : solid::PlaneMode::none;
    in.material.young = young(c);
    in.material.poisson = mesh_poisson;
    in.X = std::span<const double>(X.data(), nd);
    in.u = std::span<const double>(zero.data(), nd);
    Ke.assign(nd * nd, 0.0);
    const auto res = solid::internal_force(in, {}, Ke);
    if (res.status != solid::KernelStatus::ok)
      SEAM_THROW(InputError, "fluid cell ", c, " of the mesh is inverted in the reference mesh (",
                 solid::describe(res.status), ")");
    K_->add_values(std::span<const PetscInt>(dofs.data(), nd),
                   std::span<const PetscInt>(dofs.data(), nd), Ke);
  }
  K_->assemble();
  for (std::int32_t n = 0; n < mesh.n_nodes(); ++n)
    if (disc_->owns_node(n) && source_[n].kind != Source::free)
      for (int i = 0; i < dim; ++i) fixed_.push_back(disc_->global_dof(n, i));
  std::sort(fixed_.begin(), fixed_.end());
  // The system matrix with the prescribed rows and columns replaced by the identity, once:
  // the same unchanged matrix every step lets PETSc keep its factorization.
  K_system_.emplace(K_->copy());
  K_system_->zero_rows_columns(fixed_);
  solver_ = std::make_unique<la::LinearSolver>(layout_.comm().get(), la::SolverKind::direct);
}

void FluidMeshMotion::value_at(const Source& s, double t, std::int32_t node, double* d) const {
  const int dim = layout_.dim();
  const double* X = &layout_.mesh().x[static_cast<std::size_t>(node) * dim];
  const double z = dim == 3 ? X[2] : 0.0;
  for (int i = 0; i < dim; ++i) d[i] = 0.0;
  if (s.kind == Source::condition) {
    const auto& bc = config_.boundary_conditions[s.index];
    for (int i = 0; i < dim; ++i) d[i] = bc.value[i](t, X[0], X[1], z);
  } else if (s.kind == Source::body) {
    const auto& e = config_.bodies[s.index].mesh_motion->displacement;
    for (int i = 0; i < dim; ++i) d[i] = e[i](t, X[0], X[1], z);
  }
}

bool FluidMeshMotion::displacement(double t, std::vector<double>& d) {
  const auto& mesh = layout_.mesh();
  const int dim = mesh.dim;
  const std::int32_t n_nodes = mesh.n_nodes();
  d.assign(static_cast<std::size_t>(n_nodes) * dim, 0.0);
  if (elastic_solve_ && !disc_) build_solve();
  if (disc_) {
    // K d = 0 in the interior, d given on the Dirichlet nodes: the free rows get
    // b = -K_free,prescribed d_prescribed, the prescribed rows their values (as
    // zero_rows_columns sets them); each owner writes its nodes, the sum replicates them.
    la::Vector x = disc_->make_vector(), b = disc_->make_vector();
    {
      la::Vector::LocalView view(x, true);
      auto v = view.values();
      for (std::int32_t n = 0; n < n_nodes; ++n)
        if (disc_->owns_node(n) && source_[n].kind != Source::free)
          value_at(source_[n], t, n, &v[disc_->local_dof(n, 0)]);
    }
    K_->mult(x, b);
    b.scale(-1.0);
    {
      la::Vector::LocalView bv(b, true), xv(x, false);
      const PetscInt first = disc_->first_owned_dof();
      for (auto dof : fixed_) bv.values()[dof - first] = xv.values()[dof - first];
    }
    if (!solver_->solve(*K_system_, b, x)) return false;
    la::Vector::LocalView view(x, false);
    const auto v = view.values();
    for (std::int32_t n = 0; n < n_nodes; ++n)
      if (elastic_[n] && disc_->owns_node(n))
        for (int i = 0; i < dim; ++i) d[n * dim + i] = v[disc_->local_dof(n, i)];
  }
  // Each owner its nodes (every cell around an owned node is held, so elastic_ and source_
  // are exact there), then the ghost nodes from their owners.
  for (std::int32_t n = 0; n < n_nodes; ++n)
    if (!elastic_[n] && layout_.owns_node(n))
      value_at(source_[n], t, n, &d[static_cast<std::size_t>(n) * dim]);
  la::Vector consistent = layout_.make_vector();
  layout_.nodal_to_vector(d, consistent);
  layout_.vector_to_nodal(consistent, d);
  return true;
}

} // namespace seam::flow
