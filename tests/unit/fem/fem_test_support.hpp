#pragma once
// Shared helpers of the fem unit tests: the list of cell types and points inside reference cells.
#include "seam/fem/cell.hpp"

#include <array>
#include <random>

namespace seam::fem::test {

inline constexpr std::array<CellType, 13> all_cell_types{
    CellType::point1, CellType::line2, CellType::line3, CellType::tri3, CellType::tri6,
    CellType::quad4,  CellType::quad8, CellType::quad9, CellType::tet4, CellType::tet10,
    CellType::hex8,   CellType::hex20, CellType::hex27};

inline bool is_simplex(CellType t) {
  return t == CellType::tri3 || t == CellType::tri6 || t == CellType::tet4 || t == CellType::tet10;
}

/// Volume (length, area) of the reference domain.
inline double reference_measure(CellType t) {
  switch (dimension(t)) {
  case 0:
    return 1.0;
  case 1:
    return 2.0;
  case 2:
    return is_simplex(t) ? 0.5 : 4.0;
  default:
    return is_simplex(t) ? 1.0 / 6.0 : 8.0;
  }
}

/// Centroid of the reference domain.
inline std::array<double, 3> reference_centroid(CellType t) {
  if (!is_simplex(t)) return {0.0, 0.0, 0.0};
  const double c = 1.0 / (dimension(t) + 1);
  return {c, c, dimension(t) == 3 ? c : 0.0};
}

/// True if xi lies in the closed reference domain (up to tol).
inline bool inside_reference(CellType t, const double* xi, double tol = 0.0) {
  const int dim = dimension(t);
  if (is_simplex(t)) {
    double sum = 0.0;
    for (int a = 0; a < dim; ++a) {
      if (xi[a] < -tol) return false;
      sum += xi[a];
    }
    return sum <= 1.0 + tol;
  }
  for (int a = 0; a < dim; ++a)
    if (xi[a] < -1.0 - tol || xi[a] > 1.0 + tol) return false;
  return true;
}

/// A uniformly random point strictly inside the reference domain of t.
inline std::array<double, 3> random_point(CellType t, std::mt19937& rng) {
  const int dim = dimension(t);
  const bool simplex = is_simplex(t);
  std::uniform_real_distribution<double> u(simplex ? 0.0 : -1.0, 1.0);
  for (;;) {
    std::array<double, 3> xi{0.0, 0.0, 0.0};
    for (int a = 0; a < dim; ++a) xi[static_cast<std::size_t>(a)] = u(rng);
    if (inside_reference(t, xi.data())) return xi;
  }
}

} // namespace seam::fem::test
