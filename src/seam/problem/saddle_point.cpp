#include "seam/problem/saddle_point.hpp"

#include "seam/common/error.hpp"

#include <petscmat.h>

#include <algorithm>
#include <map>

namespace seam::problem {

using la::check;

SaddlePoint::SaddlePoint(const std::vector<meshtying::TiedInterface>& interfaces,
                         const Discretization& disc, const Model& model)
    : interfaces_(interfaces), disc_(disc) {
  const auto& comm = disc.comm();
  const int dim = disc.dim();
  const PetscInt first = disc.first_owned_dof();
  std::vector<char> dirichlet(disc.n_owned_dofs(), 0);
  for (const auto& d : model.dirichlet) dirichlet[d.dof - first] = 1;

  for (std::size_t k = 0; k < interfaces.size(); ++k) {
    const auto& t = interfaces[k];
    if (t.strategy != io::Strategy::saddle_point) continue;
    active_ = true;
    std::vector<char> has_row(t.slave.mesh_nodes.size(), 0);
    for (const auto& e : t.operators.D) has_row[e.row] = e.value != 0.0 ? 1 : has_row[e.row];
    for (std::size_t j = 0; j < has_row.size(); ++j) {
      const auto s = t.slave.mesh_nodes[j];
      if (!has_row[j] || !disc.owns_node(s)) continue;
      for (int c = 0; c < dim; ++c)
        if (!dirichlet[disc.global_dof(s, c) - first]) lm_dofs_.push_back({k, j, c});
    }
  }
  active_ = comm.any(active_);
  if (!active_) return;

  n_lm_ = static_cast<PetscInt>(lm_dofs_.size());
  std::vector<PetscInt> counts(comm.size(), 0);
  PetscInt mine = n_lm_;
  MPI_Allgather(&mine, 1, MPIU_INT, counts.data(), 1, MPIU_INT, comm.get());
  all_first_lm_.assign(comm.size() + 1, 0);
  for (int r = 0; r < comm.size(); ++r) all_first_lm_[r + 1] = all_first_lm_[r] + counts[r];
  first_lm_ = all_first_lm_[comm.rank()];
  aug_offset_ = first_lm_;

  // B: multiplier rows x displacement columns.
  check(MatCreateAIJ(comm.get(), n_lm_, disc.n_owned_dofs(), PETSC_DETERMINE, PETSC_DETERMINE, 64,
                     nullptr, 64, nullptr, &B_),
        "MatCreateAIJ");
  check(MatSetOption(B_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_FALSE), "MatSetOption");
  // B = [D T^{-1} on the slave dofs, -M on the master dofs]: the constraint holds for the
  // coefficients of the slave basis, D d~_S = M d_M, and with a modified quadratic basis
  // (dual multipliers on tri6/quad8) the unknowns are the nodal values d_S = T d~_S, so
  // d~_S = T^{-1} d_S (T = I otherwise). Columns of bound slave nodes (boundary-modified
  // basis) are prescribed dofs; the Dirichlet elimination moves them to the right-hand side.
  std::vector<std::vector<std::vector<std::pair<local_index, double>>>> inverse(interfaces.size());
  for (std::size_t k = 0; k < interfaces.size(); ++k) {
    const auto& t = interfaces[k];
    if (t.strategy != io::Strategy::saddle_point || t.operators.T.empty()) continue;
    inverse[k].resize(t.slave.mesh_nodes.size());
    for (const auto& e : mortar::inverse_transformation(t.operators.T))
      inverse[k][e.row].emplace_back(e.col, e.value);
  }
  const auto row_range = [](const std::vector<mortar::Triplet>& a, std::size_t row) {
    const auto less = [](const mortar::Triplet& x, local_index r) { return x.row < r; };
    const auto begin = std::lower_bound(a.begin(), a.end(), static_cast<local_index>(row), less);
    auto end = begin;
    while (end != a.end() && end->row == static_cast<local_index>(row)) ++end;
    return std::pair{begin, end};
  };
  for (PetscInt i = 0; i < n_lm_; ++i) {
    const auto& lm = lm_dofs_[i];
    const auto& t = interfaces[lm.interface];
    const PetscInt row = first_lm_ + i;
    const auto [d_begin, d_end] = row_range(t.operators.D, lm.slave_node);
    for (auto e = d_begin; e != d_end; ++e) {
      const auto& inv = inverse[lm.interface];
      if (inv.empty() || inv[e->col].empty()) {
        const PetscInt col = disc.global_dof(t.slave.mesh_nodes[e->col], lm.component);
        check(MatSetValue(B_, row, col, e->value, ADD_VALUES), "MatSetValue");
        continue;
      }
      for (const auto& [node, v] : inv[e->col]) {
        const PetscInt col = disc.global_dof(t.slave.mesh_nodes[node], lm.component);
        check(MatSetValue(B_, row, col, e->value * v, ADD_VALUES), "MatSetValue");
      }
    }
    const auto [m_begin, m_end] = row_range(t.operators.M, lm.slave_node);
    for (auto e = m_begin; e != m_end; ++e) {
      // A distributed interface names its master nodes by global number (the solid's layout:
      // dof = number * dim + component); they need not be held here.
      const PetscInt col = t.distributed
                               ? static_cast<PetscInt>(t.master_index[e->col]) * dim + lm.component
                               : disc.global_dof(t.master.mesh_nodes[e->col], lm.component);
      check(MatSetValue(B_, row, col, -e->value, ADD_VALUES), "MatSetValue");
    }
  }
  check(MatAssemblyBegin(B_, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(B_, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  check(MatTranspose(B_, MAT_INITIAL_MATRIX, &BT_), "MatTranspose");
  lambda_ = la::Vector(comm.get(), n_lm_);
  lambda_saved_ = la::Vector(comm.get(), n_lm_);
  constraint_ = la::Vector(comm.get(), n_lm_);
}

SaddlePoint::~SaddlePoint() {
  if (B_) MatDestroy(&B_);
  if (BT_) MatDestroy(&BT_);
}

void SaddlePoint::add_interface_forces(la::Vector& r) const {
  check(MatMultAdd(BT_, lambda_.get(), r.get(), r.get()), "MatMultAdd");
}

double SaddlePoint::constraint_norm(const la::Vector& u) {
  check(MatMult(B_, u.get(), constraint_.get()), "MatMult");
  return constraint_.norm();
}

bool SaddlePoint::solve(const la::Matrix& K, const la::Vector& minus_r, const la::Vector& u,
                        const std::vector<PetscInt>& dirichlet, const la::Vector* g,
                        la::LinearSolver& solver, la::Vector& du) {
  const auto& comm = disc_.comm();
  // [K B^T; B 0] as AIJ, rows per rank: displacement dofs, then multiplier dofs.
  Mat blocks[4] = {K.get(), BT_, B_, nullptr};
  Mat nest = nullptr, aug = nullptr;
  check(MatCreateNest(comm.get(), 2, nullptr, 2, nullptr, blocks, &nest), "MatCreateNest");
  check(MatConvert(nest, MATAIJ, MAT_INITIAL_MATRIX, &aug), "MatConvert");
  MatDestroy(&nest);
  la::Matrix A = la::Matrix::adopt(aug);

  const PetscInt n_disp = disc_.n_owned_dofs();
  la::Vector b(comm.get(), n_disp + n_lm_), x(comm.get(), n_disp + n_lm_),
      gx(comm.get(), n_disp + n_lm_);
  check(MatMult(B_, u.get(), constraint_.get()), "MatMult");
  {
    la::Vector::LocalView bv(b, true), rv(minus_r, false), cv(constraint_, false);
    auto bl = bv.values();
    const auto rl = rv.values();
    const auto cl = cv.values();
    for (PetscInt i = 0; i < n_disp; ++i) bl[i] = rl[i];
    for (PetscInt i = 0; i < n_lm_; ++i) bl[n_disp + i] = -cl[i];
  }
  std::vector<PetscInt> rows;
  rows.reserve(dirichlet.size());
  for (auto d : dirichlet) rows.push_back(d + aug_offset_);
  if (g) {
    la::Vector::LocalView xv(gx, true), gv(*g, false);
    auto xl = xv.values();
    const auto gl = gv.values();
    for (PetscInt i = 0; i < n_disp; ++i) xl[i] = gl[i];
  }
  A.zero_rows_columns(rows, g ? &gx : nullptr, g ? &b : nullptr);
  solver.set_saddle_point_fields(n_disp, n_lm_, K);
  if (!solver.solve(A, b, x)) return false;
  {
    la::Vector::LocalView xv(x, false), dv(du, true), lv(lambda_, true);
    const auto xl = xv.values();
    auto dl = dv.values();
    auto ll = lv.values();
    for (PetscInt i = 0; i < n_disp; ++i) dl[i] = xl[i];
    for (PetscInt i = 0; i < n_lm_; ++i) ll[i] += xl[n_disp + i];
  }
  return true;
}

void SaddlePoint::save() {
  lambda_saved_.copy_from(lambda_);
}
void SaddlePoint::restore() {
  lambda_.copy_from(lambda_saved_);
}

std::vector<double> SaddlePoint::multipliers(std::size_t k) const {
  const int dim = disc_.dim();
  std::vector<double> out(interfaces_[k].slave.mesh_nodes.size() * dim, 0.0);
  if (active_) {
    la::Vector::LocalView lv(lambda_, false);
    const auto ll = lv.values();
    for (PetscInt i = 0; i < n_lm_; ++i)
      if (lm_dofs_[i].interface == k)
        out[lm_dofs_[i].slave_node * dim + lm_dofs_[i].component] = ll[i];
  }
  if (!interfaces_[k].distributed) disc_.comm().sum_in_place(out);
  return out;
}

void SaddlePoint::set_multipliers(const std::vector<std::vector<double>>& values) {
  if (!active_) return;
  const int dim = disc_.dim();
  {
    la::Vector::LocalView lv(lambda_, true);
    auto ll = lv.values();
    for (PetscInt i = 0; i < n_lm_; ++i)
      ll[i] = values[lm_dofs_[i].interface][lm_dofs_[i].slave_node * dim + lm_dofs_[i].component];
  }
  lambda_saved_.copy_from(lambda_);
}

void SaddlePoint::owned_multipliers(std::size_t k, std::vector<std::int64_t>& keys,
                                    std::vector<double>& values) const {
  const int dim = disc_.dim();
  keys.clear();
  values.clear();
  if (!active_) return;
  la::Vector::LocalView lv(lambda_, false);
  const auto ll = lv.values();
  for (PetscInt i = 0; i < n_lm_; ++i) {
    const auto& d = lm_dofs_[i];
    if (d.interface != k) continue;
    keys.push_back(disc_.node_gid(interfaces_[k].slave.mesh_nodes[d.slave_node]) * dim +
                   d.component);
    values.push_back(ll[i]);
  }
}

void SaddlePoint::set_owned_multipliers(std::size_t k, std::span<const double> values) {
  if (!active_) return;
  {
    la::Vector::LocalView lv(lambda_, true);
    auto ll = lv.values();
    std::size_t next = 0;
    for (PetscInt i = 0; i < n_lm_; ++i)
      if (lm_dofs_[i].interface == k) ll[i] = values[next++];
    SEAM_ASSERT(next == values.size());
  }
  lambda_saved_.copy_from(lambda_);
}

} // namespace seam::problem
