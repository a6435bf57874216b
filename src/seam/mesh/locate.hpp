#pragma once
// Point location: which cell contains a physical point, and at which reference coordinates.
#include "seam/mesh/cell_geometry.hpp"
#include "seam/mesh/mesh.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace seam::mesh {

struct PointLocation {
  std::int32_t cell = -1;
  std::array<double, 3> xi{}; ///< reference coordinates; x(xi) equals the point to round-off
};

/// Reference coordinates xi of the physical point p in cell c: Newton on x(xi) = p (inverse
/// isoparametric map) from the reference centre. nullopt if Newton does not converge (p far
/// outside the cell or the cell degenerate); xi may lie outside the reference cell.
std::optional<std::array<double, 3>> inverse_map(const Mesh& mesh, std::int32_t c,
                                                 std::span<const double> p);

/// How far xi lies outside the reference domain of t, in reference units (0 inside; e.g. for
/// a hex max_a(|xi_a| - 1), for a tet max(-xi_a, sum xi - 1)).
double reference_distance(fem::CellType t, const double* xi);

/// Locates points by brute force over cells, each filtered by its (precomputed) bounding box.
class PointLocator {
public:
  explicit PointLocator(const Mesh& mesh);
  /// Only among `cells` (sorted), e.g. the cells a rank assembles.
  PointLocator(const Mesh& mesh, std::span<const std::int32_t> cells);

  /// The cell containing point (mesh.dim values) and its reference coordinates. A point on a
  /// facet shared by cells goes to the lowest-index cell. tol is in reference units: a point
  /// at reference distance <= tol outside the nearest cell still counts (the closest such
  /// cell is returned, xi unclamped). nullopt if no cell contains the point.
  std::optional<PointLocation> locate(std::span<const double> point, double tol = 1e-10) const;

private:
  void fill_boxes();

  const Mesh* mesh_;
  std::vector<std::int32_t> cells_; // the cells searched, increasing
  std::vector<double> boxes_;       // per searched cell: lower[3], upper[3]
};

/// One-off convenience: PointLocator(mesh).locate(point, tol).
std::optional<PointLocation> locate_point(const Mesh& mesh, std::span<const double> point,
                                          double tol = 1e-10);

} // namespace seam::mesh
