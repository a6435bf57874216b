#include "seam/mortar/dual_basis.hpp"

#include <array>

#include <Eigen/Cholesky>

#include "seam/common/error.hpp"

namespace seam::mortar {

namespace {

using fem::CellType;

constexpr std::array<EdgeNode, 1> line3_edges = {{{2, 0, 1}}};
constexpr std::array<EdgeNode, 3> tri6_edges = {{{3, 0, 1}, {4, 1, 2}, {5, 2, 0}}};
constexpr std::array<EdgeNode, 4> quad_edges = {{{4, 0, 1}, {5, 1, 2}, {6, 2, 3}, {7, 3, 0}}};

} // namespace

double basis_modification(CellType type, Multiplier multiplier) {
  if (multiplier != Multiplier::dual) return 0.0;
  return type == CellType::tri6 || type == CellType::quad8 ? 0.2 : 0.0;
}

std::span<const EdgeNode> edge_nodes(CellType type) {
  switch (type) {
  case CellType::line3:
    return line3_edges;
  case CellType::tri6:
    return tri6_edges;
  case CellType::quad8:
  case CellType::quad9:
    return quad_edges;
  default:
    return {};
  }
}

void modify_basis(CellType type, double a, double* N) {
  if (a == 0.0) return;
  for (const EdgeNode& e : edge_nodes(type)) {
    const double edge_value = N[e.node];
    N[e.v0] += a * edge_value;
    N[e.v1] += a * edge_value;
    N[e.node] = (1.0 - 2.0 * a) * edge_value;
  }
}

SmallMatrix transformation_matrix(CellType type, double a) {
  const int n = fem::n_nodes(type);
  SmallMatrix T = SmallMatrix::Identity(n, n);
  if (a == 0.0) return T;
  // u = sum N_i d_i = sum N~_i d~_i; collecting the N_e terms of the right-hand side gives
  // d_e = (1 - 2a) d~_e + a (d~_v0 + d~_v1) and d_v = d~_v.
  for (const EdgeNode& e : edge_nodes(type)) {
    T(e.node, e.node) = 1.0 - 2.0 * a;
    T(e.node, e.v0) = a;
    T(e.node, e.v1) = a;
  }
  return T;
}

template <int Dim> SmallMatrix dual_coefficients(const Facet<Dim>& facet, double a) {
  const int n = facet.n_nodes;
  // On a flat facet J is a polynomial: of degree 2p - 1 per direction on a quad of order p,
  // 2p - 2 on a triangle, p - 1 on a straight line; with N~_j N~_k (degree 2p) the integrand
  // has degree at most 4p - 1, so this rule makes D_e and M_e exact for every flat facet.
  const auto rule = fem::quadrature(facet.type, 4 * fem::order(facet.type));
  SmallMatrix M = SmallMatrix::Zero(n, n);
  SmallMatrix D = SmallMatrix::Zero(n, n);
  double measure = 0.0;
  for (int q = 0; q < rule.n_points; ++q) {
    const auto point = evaluate(facet, rule.points.data() + q * (Dim - 1));
    const double jw =
        scaled_normal<Dim>(point.dx).norm() * rule.weights[static_cast<std::size_t>(q)];
    NodalVector N = point.N;
    modify_basis(facet.type, a, N.data());
    M.noalias() += jw * N.head(n) * N.head(n).transpose();
    D.diagonal() += jw * N.head(n);
    measure += jw;
  }
  const Eigen::LDLT<SmallMatrix> ldlt(M);
  SEAM_CHECK(measure > 0.0 && ldlt.info() == Eigen::Success && ldlt.isPositive() &&
                 ldlt.vectorD().minCoeff() > 1e-14 * measure,
             InputError, "dual Lagrange multipliers: the ", fem::name(facet.type),
             " slave facet is degenerate (its mass matrix is singular)");
  // A = D M^{-1} = (M^{-1} D)^T since M is symmetric.
  return ldlt.solve(D).transpose();
}

template <int Dim> SlaveBasis make_slave_basis(const Facet<Dim>& facet, Multiplier multiplier) {
  SlaveBasis basis;
  basis.multiplier = multiplier;
  basis.modification = basis_modification(facet.type, multiplier);
  if (multiplier == Multiplier::dual) {
    basis.A = dual_coefficients(facet, basis.modification);
  }
  return basis;
}

SmallMatrix boundary_transformation(int n_nodes, unsigned bound_mask) {
  SEAM_ASSERT(n_nodes > 0 && n_nodes <= max_facet_nodes);
  SmallMatrix R = SmallMatrix::Zero(n_nodes, n_nodes);
  int n_free = 0;
  for (int i = 0; i < n_nodes; ++i) n_free += ((bound_mask >> i) & 1U) == 0 ? 1 : 0;
  if (n_free == 0) return R;
  const double share = 1.0 / n_free;
  for (int i = 0; i < n_nodes; ++i) {
    if (((bound_mask >> i) & 1U) != 0) continue;
    R(i, i) = 1.0;
    for (int b = 0; b < n_nodes; ++b) {
      if (((bound_mask >> b) & 1U) != 0) R(i, b) = share;
    }
  }
  return R;
}

template SmallMatrix dual_coefficients<2>(const Facet<2>&, double);
template SmallMatrix dual_coefficients<3>(const Facet<3>&, double);
template SlaveBasis make_slave_basis<2>(const Facet<2>&, Multiplier);
template SlaveBasis make_slave_basis<3>(const Facet<3>&, Multiplier);

} // namespace seam::mortar
