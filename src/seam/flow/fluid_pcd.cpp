#include "seam/flow/fluid_pcd.hpp"

#include "seam/common/error.hpp"
#include "seam/flow/fluid_layout.hpp"
#include "seam/flow/fluid_model.hpp"
#include "seam/fluid/pressure_operators.hpp"
#include "seam/mesh/cell_geometry.hpp"
#include "seam/mesh/facets.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace seam::flow {

namespace {

constexpr int max_vertices = 8;
constexpr int max_coordinates = fem::max_cell_nodes * 3;

// The Jacobi-preconditioned CG iterations that stand for M~^-1: the diagonal and the consistent
// mass matrix are spectrally equivalent independently of h (Wathen 1987), so a fixed number of
// iterations keeps the approximation's quality under refinement.
constexpr PetscInt mass_iterations = 5;

// Every pressure dof's index in the pressure numbering (the Schur block's rows: the owned
// pressure dofs of each rank ascending, ranks in order), on this rank's owned and ghost nodes.
la::Vector pressure_numbering(const FluidLayout& layout, PetscInt& n_owned) {
  std::vector<PetscInt> velocity, pressure;
  layout.owned_fields(velocity, pressure);
  n_owned = static_cast<PetscInt>(pressure.size());
  PetscInt offset = 0;
  MPI_Exscan(&n_owned, &offset, 1, MPIU_INT, MPI_SUM, layout.comm().get());
  if (layout.comm().rank() == 0) offset = 0;
  auto index = layout.make_vector();
  {
    la::Vector::LocalView view(index, true);
    auto v = view.values();
    for (std::size_t i = 0; i < pressure.size(); ++i)
      v[pressure[i] - layout.first_owned_dof()] = static_cast<double>(offset + PetscInt(i));
  }
  index.update_ghosts();
  return index;
}

// The pressure operators of cell c (fluid::pressure_operators) in the configuration `x` (nodal,
// mesh.x's layout) at the nodal velocity read from `u`, the fluid's local vector form (empty: at
// rest), convecting with u - w (`w` nodal, empty: a fixed mesh), in M, A, N; returns false if
// inverted.
struct CellOperators {
  int n_vertices = 0;
  std::array<double, max_vertices * max_vertices> M{}, A{}, N{};
};
bool cell_operators(const FluidLayout& layout, std::int32_t c, std::span<const double> x,
                    std::span<const double> u, std::span<const double> w, CellOperators& out) {
  const auto& mesh = layout.mesh();
  const int dim = layout.dim();
  const auto type = mesh.cell_type[c];
  const auto nodes = mesh.cell(c);
  std::array<double, max_coordinates> xc{}, velocity{}, mesh_velocity{};
  for (std::size_t a = 0; a < nodes.size(); ++a)
    for (int i = 0; i < dim; ++i) {
      const auto k = static_cast<std::size_t>(nodes[a]) * dim + i;
      xc[a * dim + i] = x[k];
      velocity[a * dim + i] = u.empty() ? 0.0 : u[layout.local_dof(nodes[a], i)];
      mesh_velocity[a * dim + i] = w.empty() ? 0.0 : w[k];
    }
  out.n_vertices = fem::n_vertices(type);
  const auto n = nodes.size() * static_cast<std::size_t>(dim);
  const auto nn = static_cast<std::size_t>(out.n_vertices * out.n_vertices);
  return fluid::pressure_operators(
      type, std::span<const double>(xc.data(), n), std::span<const double>(velocity.data(), n),
      std::span<const double>(mesh_velocity.data(), n), std::span(out.M.data(), nn),
      std::span(out.A.data(), nn), std::span(out.N.data(), nn));
}

// A KSP of its own options prefix on `A`, its defaults set before the command line's.
KSP inner_solver(const la::Matrix& A, const char* prefix, KSPType type, PCType pc_type,
                 PetscInt iterations) {
  MPI_Comm comm = MPI_COMM_NULL;
  la::check(PetscObjectGetComm(reinterpret_cast<PetscObject>(A.get()), &comm),
            "PetscObjectGetComm");
  KSP ksp = nullptr;
  la::check(KSPCreate(comm, &ksp), "KSPCreate");
  la::check(KSPSetOptionsPrefix(ksp, prefix), "KSPSetOptionsPrefix");
  la::check(KSPSetType(ksp, type), "KSPSetType");
  PC pc = nullptr;
  la::check(KSPGetPC(ksp, &pc), "KSPGetPC");
  la::check(PCSetType(pc, pc_type), "PCSetType");
  if (iterations > 0) {
    // A fixed number of iterations: the same work in every application.
    la::check(KSPSetTolerances(ksp, 0.0, 0.0, PETSC_DEFAULT, iterations), "KSPSetTolerances");
    la::check(KSPSetNormType(ksp, KSP_NORM_NONE), "KSPSetNormType");
    la::check(KSPSetConvergenceTest(ksp, KSPConvergedSkip, nullptr, nullptr),
              "KSPSetConvergenceTest");
  }
  la::check(KSPSetOperators(ksp, A.get(), A.get()), "KSPSetOperators");
  la::check(KSPSetFromOptions(ksp), "KSPSetFromOptions");
  return ksp;
}

} // namespace

bool pcd_requested() {
  char value[64] = "";
  PetscBool set = PETSC_FALSE;
  la::check(PetscOptionsGetString(nullptr, nullptr, "-fluid_schur", value, sizeof value, &set),
            "PetscOptionsGetString");
  if (!set) return false;
  const std::string v = value;
  SEAM_CHECK(v == "pcd" || v == "selfp", InputError, "command line: -fluid_schur ", v,
             ": expected pcd or selfp");
  return v == "pcd";
}

PressureConvectionDiffusion::PressureConvectionDiffusion(const FluidModel& model,
                                                         const FluidLayout& layout)
    : model_(model), layout_(layout), prescribed_(layout.make_vector()),
      fallback_(layout.make_vector()), mark_(layout.make_vector()) {
  const auto& mesh = layout.mesh();
  const int dim = layout.dim();
  bool other = false;
  for (auto c : layout.local_cells()) {
    if (fluid::is_taylor_hood(mesh.cell_type[c]))
      cells_.push_back(c);
    else
      other = true;
  }
  SEAM_CHECK(!layout.comm().any(other), InputError,
             "command line: -fluid_schur pcd needs Taylor-Hood fluid cells (tri6, quad9, tet10, "
             "hex27); the mesh has linear fluid cells");
  {
    la::Vector::LocalView view(prescribed_, true);
    auto v = view.values();
    for (const auto& d : model.dirichlet) v[d.dof - layout.first_owned_dof()] = 1.0;
  }
  prescribed_.update_ghosts();
  // The exterior facets of this rank's cells and their outward normals; the outflow facets
  // (some node's velocity free) mark the fallback vertices.
  {
    la::Vector::LocalView p_view(prescribed_, false), f_view(fallback_, true);
    const auto p = p_view.values();
    auto f = f_view.values();
    const auto exterior = mesh::exterior_facets(mesh);
    for (std::int32_t k = 0; k < exterior.size(); ++k) {
      const auto c = exterior.cell[k];
      if (!layout.is_local_cell(c)) continue;
      facet_cell_.push_back(c);
      facet_local_.push_back(exterior.local[k]);
      const auto nodes = mesh.cell(c);
      const auto local = fem::facet_nodes(mesh.cell_type[c], exterior.local[k]);
      facet_tied_.push_back(!model.tied_nodes.empty() &&
                            std::all_of(local.begin(), local.end(), [&](int a) {
                              return model.tied_nodes[static_cast<std::size_t>(nodes[a])] != 0;
                            }));
      bool open = false;
      for (int a : local)
        for (int i = 0; i < dim; ++i) open = open || p[layout.local_dof(nodes[a], i)] == 0.0;
      if (open)
        for (int a : local)
          if (layout.has_pressure(nodes[a])) f[layout.local_dof(nodes[a], dim)] = 1.0;
    }
    for (const auto& d : model.dirichlet)
      if (d.dof == layout.global_dof(d.node, dim)) f[d.dof - layout.first_owned_dof()] = 1.0;
  }
  fallback_.accumulate_ghosts();
  fallback_.update_ghosts();

  PetscInt& n_owned = n_owned_;
  const auto numbering = pressure_numbering(layout, n_owned);
  la::Vector::LocalView n_view(numbering, false);
  const auto index = n_view.values();
  for (auto c : cells_) {
    const auto nodes = mesh.cell(c);
    const int nv = fem::n_vertices(mesh.cell_type[c]);
    // The vertices are the first nodes of the cell (Gmsh order), as in fluid::navier_stokes.
    for (int k = 0; k < nv; ++k)
      for (int l = 0; l < nv; ++l) {
        const auto dk = layout.local_dof(nodes[k], dim), dl = layout.local_dof(nodes[l], dim);
        rows_.push_back(static_cast<PetscInt>(index[dk]));
        cols_.push_back(static_cast<PetscInt>(index[dl]));
        dofs_.push_back(dk);
        dofs_.push_back(dl);
      }
  }
  // Checked on every rank before the collective set-up.
  const auto inverted = set_geometry(mesh.x);
  SEAM_CHECK(!layout.comm().any(inverted >= 0), InputError, "a fluid cell is inverted (det J <= 0)",
             inverted >= 0 ? " (cell " + std::to_string(inverted + 1) + ")" : std::string());
  const MPI_Comm comm = layout.comm().get();
  Mp_ = la::Matrix::from_triplets(comm, n_owned, rows_, cols_, mass_values_);
  Ap_ = la::Matrix::from_triplets(comm, n_owned, rows_, cols_, laplace_);
  values_.assign(rows_.size(), 0.0);
  Kp_ = la::Matrix::from_triplets(comm, n_owned, rows_, cols_, values_);
  ksp_m_ = inner_solver(Mp_, "pcd_mass_", KSPCG, PCJACOBI, mass_iterations);
  la::check(MatCreateVecs(Ap_.get(), &t1_, &t2_), "MatCreateVecs");
}

PressureConvectionDiffusion::~PressureConvectionDiffusion() {
  if (ksp_a_) KSPDestroy(&ksp_a_);
  if (ksp_m_) KSPDestroy(&ksp_m_);
  if (ksp_r_) KSPDestroy(&ksp_r_);
  if (t1_) VecDestroy(&t1_);
  if (t2_) VecDestroy(&t2_);
}

std::int32_t PressureConvectionDiffusion::set_geometry(std::span<const double> x) {
  const auto& mesh = layout_.mesh();
  geometry_.assign(x.begin(), x.end());
  mass_values_.resize(rows_.size());
  laplace_.resize(rows_.size());
  CellOperators ops;
  std::int32_t inverted = -1;
  std::size_t t = 0;
  for (auto c : cells_) {
    const int nv = fem::n_vertices(mesh.cell_type[c]);
    if (!cell_operators(layout_, c, x, {}, {}, ops)) {
      inverted = c;
      t += static_cast<std::size_t>(nv * nv);
      continue;
    }
    const double mu = model_.fluids[model_.cell_fluid[c]].viscosity;
    for (int kl = 0; kl < nv * nv; ++kl, ++t) {
      mass_values_[t] = ops.M[kl] / mu;
      laplace_[t] = ops.A[kl];
    }
  }
  facet_normal_.clear();
  for (std::size_t k = 0; k < facet_cell_.size(); ++k) {
    const auto c = facet_cell_[k];
    const auto centre = mesh::reference_centre(fem::facet_type(mesh.cell_type[c], facet_local_[k]));
    facet_normal_.push_back(
        mesh::facet_normal(mesh, c, facet_local_[k], centre.data(), nullptr, x.data()));
  }
  return inverted;
}

void PressureConvectionDiffusion::mark_dirichlet(std::span<const double> u,
                                                 std::span<const double> mesh_velocity) {
  const auto& mesh = layout_.mesh();
  const int dim = layout_.dim();
  mark_.zero();
  bool any_inflow = false;
  {
    la::Vector::LocalView p_view(prescribed_, false), m_view(mark_, true);
    const auto p = p_view.values();
    auto m = m_view.values();
    for (std::size_t k = 0; k < facet_cell_.size(); ++k) {
      const auto nodes = mesh.cell(facet_cell_[k]);
      const auto local = fem::facet_nodes(mesh.cell_type[facet_cell_[k]], facet_local_[k]);
      bool prescribed = true;
      double flux = 0.0, speed = 0.0;
      for (int a : local)
        for (int i = 0; i < dim; ++i) {
          const auto dof = layout_.local_dof(nodes[a], i);
          prescribed = prescribed && p[dof] != 0.0;
          // The convective velocity u - w crosses the facet.
          const double c =
              u[dof] - (mesh_velocity.empty() ? 0.0 : mesh_velocity[nodes[a] * dim + i]);
          flux += c * facet_normal_[k][i];
          speed += std::abs(c);
        }
      // Inflow: the velocity prescribed and entering (a wall's c . n is round-off), or a side
      // of a tied interface through which the flow enters this subdomain (its pressure space
      // ends there: the pressure is not tied).
      if (!(prescribed || facet_tied_[k]) || !(flux < -1e-8 * speed)) continue;
      any_inflow = true;
      for (int a : local)
        if (layout_.has_pressure(nodes[a])) m[layout_.local_dof(nodes[a], dim)] = 1.0;
    }
  }
  mark_.accumulate_ghosts();
  mark_.update_ghosts();
  if (!layout_.comm().any(any_inflow)) mark_.copy_from(fallback_);
}

void PressureConvectionDiffusion::update(const la::Vector& w, const PcdWeights& weights,
                                         std::span<const double> x,
                                         std::span<const double> mesh_velocity) {
  const auto& mesh = layout_.mesh();
  if (x.empty()) x = mesh.x;
  la::Vector::LocalView view(w, false);
  const auto u = view.values();
  // A moved mesh: M~, A_p and A_r of the current configuration, their solvers set up again.
  const bool moved =
      layout_.comm().any(!std::equal(x.begin(), x.end(), geometry_.begin(), geometry_.end()));
  if (moved) {
    set_geometry(x); // the solver has checked the cells
    Mp_.set_triplet_values(mass_values_);
    la::check(KSPSetOperators(ksp_m_, Mp_.get(), Mp_.get()), "KSPSetOperators");
    if (ksp_r_) KSPDestroy(&ksp_r_);
  }
  // A_p's Dirichlet vertices at this velocity; its AMG hierarchy is rebuilt when they change.
  mark_dirichlet(u, mesh_velocity);
  bool changed = moved;
  {
    la::Vector::LocalView m_view(mark_, false);
    const auto m = m_view.values();
    std::vector<char> fixed(rows_.size());
    for (std::size_t t = 0; t < rows_.size(); ++t) {
      const auto dk = dofs_[2 * t], dl = dofs_[2 * t + 1];
      fixed[t] = dk != dl && (m[dk] > 0.0 || m[dl] > 0.0);
    }
    changed = layout_.comm().any(fixed != fixed_) || changed;
    fixed_ = std::move(fixed);
  }
  if (changed || !ksp_a_) {
    for (std::size_t t = 0; t < rows_.size(); ++t) values_[t] = fixed_[t] ? 0.0 : laplace_[t];
    Ap_.set_triplet_values(values_);
    if (ksp_a_) KSPDestroy(&ksp_a_);
    ksp_a_ = inner_solver(Ap_, "pcd_laplace_", KSPPREONLY, PCHYPRE, 0);
  }
  CellOperators ops;
  std::size_t t = 0;
  for (auto cell : cells_) {
    cell_operators(layout_, cell, x, u, mesh_velocity, ops);
    const auto nn = static_cast<std::size_t>(ops.n_vertices * ops.n_vertices);
    const auto& fluid = model_.fluids[model_.cell_fluid[cell]];
    const double scale = fluid.density / fluid.viscosity;
    for (std::size_t kl = 0; kl < nn; ++kl, ++t) values_[t] = scale * weights.state * ops.N[kl];
  }
  Kp_.set_triplet_values(values_);
  if (weights.mass > 0.0 && !ksp_r_) {
    // The reaction's Laplacian, weighted by 1/rho, with the Dirichlet vertices of the outflow.
    la::Vector::LocalView f_view(fallback_, false);
    const auto f = f_view.values();
    t = 0;
    for (auto cell : cells_) {
      const auto& fluid = model_.fluids[model_.cell_fluid[cell]];
      const int nv = fem::n_vertices(mesh.cell_type[cell]);
      for (int kl = 0; kl < nv * nv; ++kl, ++t) {
        const auto dk = dofs_[2 * t], dl = dofs_[2 * t + 1];
        values_[t] = dk != dl && (f[dk] > 0.0 || f[dl] > 0.0) ? 0.0 : laplace_[t] / fluid.density;
      }
    }
    if (Ar_.get() == nullptr)
      Ar_ = la::Matrix::from_triplets(layout_.comm().get(), n_owned_, rows_, cols_, values_);
    else
      Ar_.set_triplet_values(values_);
    ksp_r_ = inner_solver(Ar_, "pcd_reaction_", KSPPREONLY, PCHYPRE, 0);
  }
  mass_ = weights.mass;
  state_ = weights.state;
  coupling_ = weights.coupling;
}

void PressureConvectionDiffusion::apply(Vec x, Vec y) const {
  la::check(KSPSolve(ksp_a_, x, t1_), "KSPSolve (PCD, A_p)");
  la::check(MatMult(Kp_.get(), t1_, t2_), "MatMult (PCD, K_p)");
  la::check(VecAXPY(t2_, state_, x), "VecAXPY");
  la::check(KSPSolve(ksp_m_, t2_, y), "KSPSolve (PCD, M_p)");
  if (mass_ > 0.0) {
    la::check(KSPSolve(ksp_r_, x, t1_), "KSPSolve (PCD, reaction)");
    la::check(VecAXPY(y, mass_, t1_), "VecAXPY");
  }
  la::check(VecScale(y, -1.0 / coupling_), "VecScale");
}

} // namespace seam::flow
