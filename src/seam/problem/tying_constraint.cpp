#include "seam/problem/tying_constraint.hpp"

#include "seam/common/error.hpp"
#include "seam/parallel/exchange.hpp"

#include <algorithm>
#include <limits>
#include <map>

namespace seam::problem {

namespace {

/// Nodes some rank found at fault (by their ids in the mesh as read).
struct Offenders {
  std::vector<std::int64_t> ids;
  void add(std::int64_t id) { ids.push_back(id); }
  struct Agreed {
    std::int64_t count = 0; ///< the ranks' distinct ids summed
    std::int64_t first = -1;
  };
  /// Collective: the same on every rank; first -1 if no rank found any.
  Agreed agree(const Comm& comm) {
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    Agreed a{static_cast<std::int64_t>(ids.size()),
             ids.empty() ? std::numeric_limits<std::int64_t>::max() : ids.front()};
    MPI_Allreduce(MPI_IN_PLACE, &a.count, 1, MPI_INT64_T, MPI_SUM, comm.get());
    MPI_Allreduce(MPI_IN_PLACE, &a.first, 1, MPI_INT64_T, MPI_MIN, comm.get());
    if (a.count == 0) a.first = -1;
    return a;
  }
};

} // namespace

TyingConstraint::TyingConstraint(const std::vector<meshtying::TiedInterface>& interfaces,
                                 TiedDofs dofs)
    : interfaces_(interfaces), dofs_(std::move(dofs)) {
  const auto& disc = dofs_;
  const int dim = disc.dim;
  const PetscInt first = disc.first_owned;
  const PetscInt n_owned = disc.n_owned;
  std::vector<char> dirichlet(n_owned, 0);
  for (auto dof : disc.prescribed) dirichlet[dof - first] = 1;

  // Rows of T owned here: global column -> value, for the eliminated dofs.
  std::map<PetscInt, std::vector<std::pair<PetscInt, double>>> rows;
  std::vector<char> is_slave_node(disc.mesh->n_nodes(), 0);
  for (const auto& t : interfaces)
    for (auto n : t.slave.mesh_nodes) is_slave_node[n] = 1;

  // The first dofs of the master nodes of distributed interfaces, by global node number, if
  // the layout is not the solid's (one collective lookup for all interfaces).
  std::vector<std::int64_t> master_numbers;
  std::vector<PetscInt> master_first;
  if (disc.first_dofs_of) {
    for (const auto& t : interfaces)
      if (t.distributed && t.strategy == io::Strategy::condensed)
        master_numbers.insert(master_numbers.end(), t.master_index.begin(), t.master_index.end());
    std::sort(master_numbers.begin(), master_numbers.end());
    master_numbers.erase(std::unique(master_numbers.begin(), master_numbers.end()),
                         master_numbers.end());
    master_first = disc.first_dofs_of(master_numbers);
  }
  const auto master_dof = [&](std::int64_t number, int c) -> PetscInt {
    if (!disc.first_dofs_of) return static_cast<PetscInt>(number) * dim + c;
    const auto at = std::lower_bound(master_numbers.begin(), master_numbers.end(), number);
    return master_first[static_cast<std::size_t>(at - master_numbers.begin())] + c;
  };

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
    // The constraint for the free slave nodes S, with the bound nodes B (every component
    // prescribed; boundary-modified basis, mortar/dual_basis.hpp) on the known side:
    //   D_SS d~_S = M d_M - D_SB d~_B,  d~_B = (T^{-1} d)_B,
    // and d_S = T d~_S for a modified quadratic basis (dual multipliers on tri6/quad8,
    // ALGORITHMS.md §3). Each eliminated slave displacement becomes a combination of master
    // displacements and prescribed slave displacements: d = P [d_M; d_B].
    const auto T_inverse = mortar::inverse_transformation(ops.T);
    std::vector<std::vector<std::pair<local_index, double>>> inverse_row(diag.size());
    for (const auto& e : T_inverse) inverse_row[e.row].emplace_back(e.col, e.value);
    const auto known_tilde = [&](local_index b) {
      return inverse_row[b].empty() ? std::vector<std::pair<local_index, double>>{{b, 1.0}}
                                    : inverse_row[b];
    };
    // Column key: master node l -> l, slave node m -> -1 - m.
    using Row = std::map<local_index, double>;
    std::vector<Row> tilde(diag.size());
    for (const auto& e : ops.M)
      if (diag[e.row] != 0.0) tilde[e.row][e.col] += e.value / diag[e.row];
    for (const auto& e : ops.D) {
      if (e.row == e.col || diag[e.row] == 0.0) continue;
      SEAM_ASSERT(!ops.bound.empty() && ops.bound[e.col] != 0);
      for (const auto& [m, v] : known_tilde(e.col))
        tilde[e.row][-1 - m] -= e.value / diag[e.row] * v;
    }
    std::vector<Row> P(diag.size());
    std::vector<char> tied(diag.size(), 0);
    Offenders twice, chained;
    const auto add_term = [&](local_index j, local_index node, double weight) {
      if (diag[node] != 0.0) {
        tied[j] = 1;
        for (const auto& [col, v] : tilde[node]) P[j][col] += weight * v;
      } else if (!ops.bound.empty() && ops.bound[node] != 0) {
        for (const auto& [m, v] : known_tilde(node)) P[j][-1 - m] += weight * v;
      }
    };
    if (ops.T.empty()) {
      for (std::size_t j = 0; j < diag.size(); ++j)
        add_term(static_cast<local_index>(j), static_cast<local_index>(j), 1.0);
    } else {
      for (const auto& e : ops.T) add_term(e.row, e.col, e.value);
    }
    for (std::size_t j = 0; j < diag.size(); ++j) {
      const auto s = t.slave.mesh_nodes[j];
      if (!tied[j] || !disc.owns_node(s)) continue;
      for (int c = 0; c < dim; ++c) {
        const PetscInt row = disc.global_dof(s, c);
        // A partially prescribed node (a symmetry plane) keeps its multiplier; its prescribed
        // components are not tied.
        if (dirichlet[row - first]) continue;
        auto& entries = rows[row];
        if (!entries.empty()) {
          twice.add(disc.node_id(s));
          break;
        }
        for (const auto& [key, v] : P[j]) {
          if (key < 0) {
            entries.emplace_back(disc.global_dof(t.slave.mesh_nodes[-1 - key], c), v);
            continue;
          }
          if (t.distributed) { // global node number (the solid's layout); chains checked at set-up
            entries.emplace_back(master_dof(t.master_index[key], c), v);
            continue;
          }
          const auto master = t.master.mesh_nodes[key];
          if (is_slave_node[master]) chained.add(disc.node_id(master));
          entries.emplace_back(disc.global_dof(master, c), v);
        }
      }
    }
    // Found by the slave nodes' owners: thrown on every rank alike.
    if (const auto n = twice.agree(disc.comm); n.first >= 0)
      SEAM_THROW(InputError, "interface '", t.name, "': ", n.count,
                 n.count == 1 ? " slave node is" : " slave nodes are",
                 " tied by two interfaces (the first: node ", n.first,
                 "); slave sides must not share nodes");
    if (const auto n = chained.agree(disc.comm); n.first >= 0)
      SEAM_THROW(InputError, "interface '", t.name, "': master node ", n.first,
                 " is a slave node of another interface; chained tying is not supported");
    if (!ops.T.empty()) transforms_[k] = ops.T;
  }
  active_ = disc.comm.any(active_);
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
    ++d_nnz[i]; // the explicit zero on the diagonal, see below
  }
  for (const auto& [row, entries] : rows) eliminated_.push_back(row);
  T_ = la::Matrix(disc.comm.get(), n_owned, d_nnz, o_nnz, 1);
  for (PetscInt i = 0; i < n_owned; ++i) {
    const PetscInt row = first + i;
    auto it = rows.find(row);
    if (it == rows.end()) {
      const double one = 1.0;
      T_.add_values({&row, 1}, {&row, 1}, {&one, 1});
      continue;
    }
    for (const auto& [col, v] : it->second) T_.add_values({&row, 1}, {&col, 1}, {&v, 1});
    // A structural zero T_jj puts the diagonal of the eliminated dof into the pattern of
    // T^T K T, so that condense_matrix sets its unit diagonal in place; inserting it into
    // the assembled product instead reallocates the matrix storage again and again (quadratic
    // in the number of eliminated dofs).
    const double zero = 0.0;
    T_.add_values({&row, 1}, {&row, 1}, {&zero, 1});
  }
  T_.assemble();
}

void TyingConstraint::condense_matrix(const la::Matrix& K, la::Matrix& Kt) const {
  // The patterns of K and T never change: the symbolic product runs once, later calls only
  // recompute the values. On one rank the "rap" algorithm (R = T^T formed explicitly, then
  // R K T) is several times faster than PETSc's default PtAP for this T, the identity with a
  // few dense-ish rows (docs/mortar_performance.md). On several ranks "allatonce" forms the
  // product without storing K T and the off-rank rows of T in full: on the tied blocks at
  // 68 799 dofs, np 4, the largest rank's memory grew by 37 MB in the first condensation
  // instead of 84 MB with the default algorithm (docs/parallel.md, "Memory per rank").
  if (Kt.get() == nullptr || Kt.get() != last_product_ || K.get() != last_matrix_) {
    Mat C = nullptr;
    la::check(MatProductCreate(K.get(), T_.get(), nullptr, &C), "MatProductCreate");
    Kt = la::Matrix::adopt(C);
    la::check(MatProductSetType(C, MATPRODUCT_PtAP), "MatProductSetType");
    la::check(
        MatProductSetAlgorithm(C, dofs_.comm.size() == 1 ? MATPRODUCTALGORITHMRAP : "allatonce"),
        "MatProductSetAlgorithm");
    la::check(MatProductSetFill(C, 2.0), "MatProductSetFill");
    la::check(MatProductSetFromOptions(C), "MatProductSetFromOptions");
    la::check(MatProductSymbolic(C), "MatProductSymbolic");
    // Hold references, so that neither handle can be freed and its address reused by an
    // unrelated matrix while it identifies the product to reuse.
    release_product();
    la::check(PetscObjectReference(reinterpret_cast<PetscObject>(C)), "PetscObjectReference");
    la::check(PetscObjectReference(reinterpret_cast<PetscObject>(K.get())), "PetscObjectReference");
    last_product_ = C;
    last_matrix_ = K.get();
  }
  la::check(MatProductNumeric(Kt.get()), "MatProductNumeric");
  // The eliminated rows and columns of T^T K T are empty: a unit diagonal keeps it regular.
  la::Vector ones(dofs_.comm.get(), dofs_.n_owned);
  {
    la::Vector::LocalView v(ones, true);
    auto values = v.values();
    const PetscInt first = dofs_.first_owned;
    for (auto d : eliminated_) values[d - first] = 1.0;
  }
  Kt.add_diagonal(ones);
}

TyingConstraint::~TyingConstraint() {
  release_product();
}

void TyingConstraint::release_product() const {
  if (last_product_) MatDestroy(&last_product_);
  if (last_matrix_) MatDestroy(&last_matrix_);
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
  const int dim = dofs_.dim;
  const auto n = t.slave.mesh_nodes.size();
  std::vector<double> lambda(n * dim, 0.0);
  if (t.strategy != io::Strategy::condensed) return lambda;
  // The slave rows of the residual this rank owns (eliminated dofs only).
  std::vector<double> r(n * dim, 0.0);
  for (std::size_t j = 0; j < n; ++j) {
    const auto s = t.slave.mesh_nodes[j];
    if (!dofs_.owns_node(s)) continue;
    for (int c = 0; c < dim; ++c)
      if (std::binary_search(eliminated_.begin(), eliminated_.end(), dofs_.global_dof(s, c)))
        r[j * dim + c] = r_local[dofs_.local_dof(s, c)];
  }
  // Slave rows of the equilibrium: T^T r_S + D lambda = 0 (T = I without modification).
  std::vector<double> tr(n * dim, 0.0);
  if (transforms_[interface].empty()) {
    tr = r;
  } else {
    for (const auto& e : transforms_[interface])
      for (int c = 0; c < dim; ++c) tr[e.col * dim + c] += e.value * r[e.row * dim + c];
  }
  if (t.distributed) { // the rows of the neighbours in T may be owned elsewhere
    std::vector<int> owners(n);
    for (std::size_t j = 0; j < n; ++j) owners[j] = dofs_.node_owner(t.slave.mesh_nodes[j]);
    parallel::sum_on_owners(dofs_.comm.get(), t.slave_index, owners, tr, dim);
  }
  for (std::size_t j = 0; j < n; ++j) {
    const double d = d_diag_[interface][j];
    if (d == 0.0) continue;
    for (int c = 0; c < dim; ++c) lambda[j * dim + c] = -tr[j * dim + c] / d;
  }
  return lambda;
}

} // namespace seam::problem
