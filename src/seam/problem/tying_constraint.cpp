#include "seam/problem/tying_constraint.hpp"

#include "seam/common/error.hpp"

#include <algorithm>
#include <map>

namespace seam::problem {

TyingConstraint::TyingConstraint(const std::vector<meshtying::TiedInterface>& interfaces,
                                 const Discretization& disc, const Model& model)
    : interfaces_(interfaces), disc_(disc) {
  const int dim = disc.dim();
  const PetscInt first = disc.first_owned_dof();
  const PetscInt n_owned = disc.n_owned_dofs();
  std::vector<char> dirichlet(n_owned, 0);
  for (const auto& d : model.dirichlet) dirichlet[d.dof - first] = 1;

  // Rows of T owned here: global column -> value, for the eliminated dofs.
  std::map<PetscInt, std::vector<std::pair<PetscInt, double>>> rows;
  std::vector<char> is_slave_node(disc.mesh().n_nodes(), 0);
  for (const auto& t : interfaces)
    for (auto n : t.slave.mesh_nodes) is_slave_node[n] = 1;

  d_diag_.resize(interfaces.size());
  transforms_.resize(interfaces.size());
  for (std::size_t k = 0; k < interfaces.size(); ++k) {
    const auto& t = interfaces[k];
    if (t.strategy != io::Strategy::condensed) continue;
    active_ = true;
    const auto& ops = t.operators;
    auto& diag = d_diag_[k];
    diag.assign(t.slave.mesh_nodes.size(), 0.0);
    for (const auto& e : ops.D)
      if (e.row == e.col) diag[e.row] = e.value;
    // Row scale for "D_jj is zero": nodes outside the overlap are left untied.
    double d_max = 0.0;
    for (double v : diag) d_max = std::max(d_max, std::abs(v));
    for (auto& v : diag)
      if (v <= 1e-12 * d_max) v = 0.0;
    // P = D^{-1} M, side-local: slave node -> (master node, value). With a modified slave basis
    // (dual multipliers on tri6/quad8, ALGORITHMS.md §3) the constraint holds for the modified
    // coefficients, D d~_S = M d_M, and the nodal displacements are d_S = T d~_S: P = T D^{-1} M.
    std::vector<std::map<local_index, double>> P(diag.size());
    std::vector<std::vector<std::pair<local_index, double>>> dm(diag.size());
    for (const auto& e : ops.M)
      if (diag[e.row] != 0.0) dm[e.row].emplace_back(e.col, e.value / diag[e.row]);
    if (ops.T.empty()) {
      for (std::size_t j = 0; j < diag.size(); ++j)
        for (const auto& [l, v] : dm[j]) P[j][l] += v;
    } else {
      for (const auto& e : ops.T)
        for (const auto& [l, v] : dm[e.col]) P[e.row][l] += e.value * v;
    }
    for (std::size_t j = 0; j < diag.size(); ++j) {
      const auto s = t.slave.mesh_nodes[j];
      if (P[j].empty() || !disc.owns_node(s)) continue;
      for (int c = 0; c < dim; ++c) {
        const PetscInt row = disc.global_dof(s, c);
        if (dirichlet[row - first]) continue; // the prescribed value wins
        auto& entries = rows[row];
        if (!entries.empty())
          SEAM_THROW(InputError, "interface '", t.name, "': slave node ", s,
                     " is tied by two interfaces; slave sides must not share nodes");
        for (const auto& [l, v] : P[j]) {
          const auto master = t.master.mesh_nodes[l];
          if (is_slave_node[master])
            SEAM_THROW(InputError, "interface '", t.name, "': master node ", master,
                       " is a slave node of another interface; chained tying is not supported");
          entries.emplace_back(disc.global_dof(master, c), v);
        }
      }
    }
    if (!ops.T.empty()) transforms_[k] = ops.T;
  }
  active_ = disc.comm().any(active_);
  if (!active_) return;

  // T: identity on the kept dofs, P on the eliminated ones (exact preallocation).
  const PetscInt last = first + n_owned;
  std::vector<PetscInt> d_nnz(n_owned, 0), o_nnz(n_owned, 0);
  for (PetscInt i = 0; i < n_owned; ++i) {
    auto it = rows.find(first + i);
    if (it == rows.end()) {
      d_nnz[i] = 1;
      continue;
    }
    for (const auto& [col, v] : it->second) (col >= first && col < last ? d_nnz[i] : o_nnz[i])++;
  }
  for (const auto& [row, entries] : rows) eliminated_.push_back(row);
  T_ = la::Matrix(disc.comm().get(), n_owned, d_nnz, o_nnz, 1);
  for (PetscInt i = 0; i < n_owned; ++i) {
    const PetscInt row = first + i;
    auto it = rows.find(row);
    if (it == rows.end()) {
      const double one = 1.0;
      T_.add_values({&row, 1}, {&row, 1}, {&one, 1});
      continue;
    }
    for (const auto& [col, v] : it->second) T_.add_values({&row, 1}, {&col, 1}, {&v, 1});
  }
  T_.assemble();
}

void TyingConstraint::condense_matrix(const la::Matrix& K, la::Matrix& Kt) const {
  Kt = la::Matrix::ptap(K, T_);
  // The eliminated rows and columns of T^T K T are empty: a unit diagonal keeps it regular.
  la::Vector ones(disc_.comm().get(), disc_.n_owned_dofs());
  {
    la::Vector::LocalView v(ones, true);
    auto values = v.values();
    const PetscInt first = disc_.first_owned_dof();
    for (auto d : eliminated_) values[d - first] = 1.0;
  }
  Kt.add_diagonal(ones);
}

void TyingConstraint::condense_vector(const la::Vector& r, la::Vector& rt) const {
  T_.mult_transpose(r, rt);
}

void TyingConstraint::expand(const la::Vector& dut, la::Vector& du) const {
  T_.mult(dut, du);
}

std::vector<double> TyingConstraint::multipliers(std::size_t interface,
                                                 std::span<const double> r_local) const {
  const auto& t = interfaces_[interface];
  const int dim = disc_.dim();
  const auto n = t.slave.mesh_nodes.size();
  std::vector<double> lambda(n * dim, 0.0);
  if (d_diag_[interface].empty()) return lambda;
  // The slave rows of the residual this rank owns (eliminated dofs only).
  std::vector<double> r(n * dim, 0.0);
  for (std::size_t j = 0; j < n; ++j) {
    const auto s = t.slave.mesh_nodes[j];
    if (!disc_.owns_node(s)) continue;
    for (int c = 0; c < dim; ++c)
      if (std::binary_search(eliminated_.begin(), eliminated_.end(), disc_.global_dof(s, c)))
        r[j * dim + c] = r_local[disc_.local_dof(s, c)];
  }
  // Slave rows of the equilibrium: T^T r_S + D lambda = 0 (T = I without modification).
  std::vector<double> tr(n * dim, 0.0);
  if (transforms_[interface].empty()) {
    tr = r;
  } else {
    for (const auto& e : transforms_[interface])
      for (int c = 0; c < dim; ++c) tr[e.col * dim + c] += e.value * r[e.row * dim + c];
  }
  for (std::size_t j = 0; j < n; ++j) {
    const double d = d_diag_[interface][j];
    if (d == 0.0) continue;
    for (int c = 0; c < dim; ++c) lambda[j * dim + c] = -tr[j * dim + c] / d;
  }
  return lambda;
}

} // namespace seam::problem
