// Mesh initialization (ALGORITHMS.md §4): slave coordinates such that D X_S = M X_M, so the
// tying constraint D x_S = M x_M holds exactly in the reference configuration and, D and M
// being constant, for all time — the condition for conserving angular momentum (§7).
#include <unordered_map>

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include "seam/common/error.hpp"
#include "seam/mortar/interface.hpp"

namespace seam::mortar {

std::vector<double> initialize_slave_coordinates(const MortarOperators& ops,
                                                 std::span<const double> slave_coordinates,
                                                 std::span<const double> master_coordinates) {
  const int dim = ops.dim;
  SEAM_CHECK(dim == 2 || dim == 3, InputError, "initialize_slave_coordinates: operators of ",
             "dimension ", dim);
  const auto d = static_cast<std::size_t>(dim);
  const auto slave_x = [&](local_index node, int a) {
    return slave_coordinates[static_cast<std::size_t>(node) * d + static_cast<std::size_t>(a)];
  };
  std::vector<double> result(slave_coordinates.begin(), slave_coordinates.end());

  // Interface slave nodes = rows of D, numbered 0..n-1 for the solve.
  std::unordered_map<local_index, int> position;
  std::vector<local_index> rows;
  for (const Triplet& t : ops.D) {
    if (position.emplace(t.row, static_cast<int>(rows.size())).second) rows.push_back(t.row);
  }
  const int n = static_cast<int>(rows.size());
  if (n == 0) return result;

  // Coordinates in the (possibly modified) basis of the nodes that stay where they are:
  // X~ = T^{-1} X, read off the current slave coordinates.
  const std::vector<Triplet> T_inverse = inverse_transformation(ops.T);
  std::unordered_map<local_index, Eigen::Vector3d> kept_tilde;
  for (const Triplet& t : T_inverse) {
    auto& x = kept_tilde.try_emplace(t.row, Eigen::Vector3d::Zero()).first->second;
    for (int a = 0; a < dim; ++a) x(a) += t.value * slave_x(t.col, a);
  }
  const auto tilde_of_kept = [&](local_index node) {
    if (const auto it = kept_tilde.find(node); it != kept_tilde.end()) return it->second;
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int a = 0; a < dim; ++a) x(a) = slave_x(node, a);
    return x;
  };

  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, dim);
  for (const Triplet& t : ops.M) {
    const auto base = static_cast<std::size_t>(t.col) * d;
    SEAM_CHECK(base + d <= master_coordinates.size(), InputError,
               "initialize_slave_coordinates: master node ", t.col,
               " is outside the master coordinate array");
    for (int a = 0; a < dim; ++a) {
      rhs(position.at(t.row), a) +=
          t.value * master_coordinates[base + static_cast<std::size_t>(a)];
    }
  }
  // Columns of bound nodes (no row of their own): those nodes keep their place and join the
  // known side, D_SS X~_S = M X_M - D_SB X~_B.
  std::vector<Triplet> D_free;
  D_free.reserve(ops.D.size());
  for (const Triplet& t : ops.D) {
    if (position.count(t.col) == 1) {
      D_free.push_back(t);
      continue;
    }
    SEAM_CHECK(static_cast<std::size_t>(t.col) < ops.bound.size() && ops.bound[t.col] != 0,
               InternalError, "mortar D has column ", t.col, " without a row");
    const Eigen::Vector3d x = tilde_of_kept(t.col);
    for (int a = 0; a < dim; ++a) rhs(position.at(t.row), a) -= t.value * x(a);
  }

  Eigen::MatrixXd modified(n, dim);
  if (ops.multiplier == Multiplier::dual) {
    for (const Triplet& t : D_free) {
      SEAM_CHECK(t.row == t.col, InternalError, "dual mortar D is not diagonal");
      SEAM_CHECK(t.value != 0.0, InputError, "mesh initialization: slave node ", t.row,
                 " has a zero mortar diagonal");
      modified.row(position.at(t.row)) = rhs.row(position.at(t.row)) / t.value;
    }
  } else {
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(D_free.size());
    for (const Triplet& t : D_free)
      entries.emplace_back(position.at(t.row), position.at(t.col), t.value);
    Eigen::SparseMatrix<double> D(n, n);
    D.setFromTriplets(entries.begin(), entries.end());
    Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
    lu.compute(D);
    SEAM_CHECK(lu.info() == Eigen::Success, InputError,
               "mesh initialization: the mortar matrix D is singular");
    modified = lu.solve(rhs);
  }

  if (ops.T.empty()) {
    for (int i = 0; i < n; ++i) {
      for (int a = 0; a < dim; ++a) {
        result[static_cast<std::size_t>(rows[static_cast<std::size_t>(i)]) * d +
               static_cast<std::size_t>(a)] = modified(i, a);
      }
    }
    return result;
  }

  // Modified quadratic basis: the solve gives X~ of the interface nodes, every other node
  // keeps its X~ = T^{-1} X; then X = T X~. T is sorted by row, so rows are contiguous.
  const auto tilde = [&](local_index node) {
    if (const auto it = position.find(node); it != position.end()) {
      Eigen::Vector3d x = Eigen::Vector3d::Zero();
      x.head(dim) = modified.row(it->second).transpose();
      return x;
    }
    return tilde_of_kept(node);
  };
  for (std::size_t begin = 0; begin < ops.T.size();) {
    const local_index node = ops.T[begin].row;
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    bool moved = false; // a node whose row of T involves no interface node stays exactly put
    for (; begin < ops.T.size() && ops.T[begin].row == node; ++begin) {
      x += ops.T[begin].value * tilde(ops.T[begin].col);
      moved = moved || position.count(ops.T[begin].col) == 1;
    }
    if (!moved) continue;
    for (int a = 0; a < dim; ++a) {
      result[static_cast<std::size_t>(node) * d + static_cast<std::size_t>(a)] = x(a);
    }
  }
  return result;
}

} // namespace seam::mortar
