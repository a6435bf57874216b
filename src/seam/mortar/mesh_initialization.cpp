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
  for (const Triplet& t : ops.D) {
    SEAM_CHECK(position.count(t.col) == 1, InternalError, "mortar D has column ", t.col,
               " without a row");
  }

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

  Eigen::MatrixXd modified(n, dim);
  if (ops.multiplier == Multiplier::dual) {
    for (const Triplet& t : ops.D) {
      SEAM_CHECK(t.row == t.col, InternalError, "dual mortar D is not diagonal");
      SEAM_CHECK(t.value != 0.0, InputError, "mesh initialization: slave node ", t.row,
                 " has a zero mortar diagonal");
      modified.row(position.at(t.row)) = rhs.row(position.at(t.row)) / t.value;
    }
  } else {
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(ops.D.size());
    for (const Triplet& t : ops.D)
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

  // Modified quadratic basis: the solve gives X~ and X = T X~. Nodes outside D keep their
  // position, i.e. their X~ = T^{-1} X: vertex rows of T are unit rows, so an edge row gives
  // X~_e = (X_e - sum_{k != e} T_ek X_k) / T_ee. T is sorted by row, so rows are contiguous.
  std::unordered_map<local_index, Eigen::Vector3d> tilde;
  for (std::size_t begin = 0; begin < ops.T.size();) {
    std::size_t end = begin;
    while (end < ops.T.size() && ops.T[end].row == ops.T[begin].row) ++end;
    const local_index node = ops.T[begin].row;
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    if (const auto it = position.find(node); it != position.end()) {
      x.head(dim) = modified.row(it->second).transpose();
    } else {
      double diagonal = 0.0;
      for (int a = 0; a < dim; ++a) x(a) = slave_x(node, a);
      for (std::size_t e = begin; e < end; ++e) {
        if (ops.T[e].col == node) {
          diagonal = ops.T[e].value;
        } else {
          for (int a = 0; a < dim; ++a) x(a) -= ops.T[e].value * slave_x(ops.T[e].col, a);
        }
      }
      x /= diagonal;
    }
    tilde.emplace(node, x);
    begin = end;
  }
  for (std::size_t begin = 0; begin < ops.T.size();) {
    const local_index node = ops.T[begin].row;
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (; begin < ops.T.size() && ops.T[begin].row == node; ++begin) {
      x += ops.T[begin].value * tilde.at(ops.T[begin].col);
    }
    for (int a = 0; a < dim; ++a) {
      result[static_cast<std::size_t>(node) * d + static_cast<std::size_t>(a)] = x(a);
    }
  }
  return result;
}

} // namespace seam::mortar
