#pragma once
// Interface facets: the flat-array description an interface is given (FacetSet), the
// fixed-size geometry of one facet (Facet<Dim>) and its evaluation with the reference-cell
// shape functions of seam::fem. Dim is the spatial dimension: line facets in 2D (line2,
// line3), surface facets in 3D (tri3, tri6, quad4, quad8, quad9).
#include <array>
#include <span>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "seam/common/types.hpp"
#include "seam/fem/cell.hpp"
#include "seam/geometry/projection.hpp"

namespace seam::mortar {

inline constexpr int max_facet_nodes = fem::max_facet_nodes;

/// Fixed-capacity per-node vector (shape function values, multiplier values, gaps).
using NodalVector = Eigen::Matrix<double, max_facet_nodes, 1>;

/// Facets of one side of an interface as flat arrays (CSR connectivity). Node indices point
/// into `coordinates`, node-major with `dim` values per node; each facet lists its nodes in
/// seam::fem order, oriented so that its normal points out of its body.
struct FacetSet {
  int dim = 3;
  std::span<const double> coordinates;
  std::span<const fem::CellType> types; ///< one per facet
  std::span<const local_index> offsets; ///< n_facets + 1 entries into `nodes`
  std::span<const local_index> nodes;

  local_index n_facets() const { return static_cast<local_index>(types.size()); }
  local_index n_nodes() const {
    return dim > 0 ? static_cast<local_index>(coordinates.size() / static_cast<std::size_t>(dim))
                   : 0;
  }
  std::span<const local_index> facet_nodes(local_index f) const {
    return nodes.subspan(static_cast<std::size_t>(offsets[static_cast<std::size_t>(f)]),
                         static_cast<std::size_t>(offsets[static_cast<std::size_t>(f) + 1] -
                                                  offsets[static_cast<std::size_t>(f)]));
  }
};

/// Throws seam::InputError naming `side` if the arrays are inconsistent: dim not 2 or 3, facet
/// types that are not interface facets of that dimension, node counts, out-of-range indices.
void validate(const FacetSet& facets, const char* side);

/// True for line2/line3 when dim = 2 and tri3/tri6/quad4/quad8/quad9 when dim = 3.
bool is_interface_facet(fem::CellType type, int dim);

/// One facet's type and nodal coordinates (columns; unused columns are zero).
template <int Dim> struct Facet {
  fem::CellType type = Dim == 2 ? fem::CellType::line2 : fem::CellType::tri3;
  int n_nodes = 0;
  Eigen::Matrix<double, Dim, max_facet_nodes> x =
      Eigen::Matrix<double, Dim, max_facet_nodes>::Zero();
};

/// False for a quad4 that is not a parallelogram (x0 + x2 != x1 + x3): its bilinear map is
/// not affine, so the mortar integrands are not polynomials on the integration cells and no
/// cell rule integrates them exactly (Puso & Laursen 2004: the patch test then holds to
/// quadrature accuracy only). Other linear facets are affine.
template <int Dim> bool is_affine(const Facet<Dim>& f) {
  if (f.type != fem::CellType::quad4) return true;
  const auto d = (f.x.col(0) + f.x.col(2) - f.x.col(1) - f.x.col(3)).norm();
  const auto diagonal = (f.x.col(2) - f.x.col(0)).norm() + (f.x.col(3) - f.x.col(1)).norm();
  return d <= 1e-12 * diagonal;
}

/// True if every quad4 facet of a 3D set is a parallelogram (is_affine). An interface with
/// other quad4 facets is integrated with the degree-8 cell rule (PairOptions): the patch-test
/// error drops from about 1e-4 to 1e-6 there. The choice is made once per interface, so that
/// the rule stays the same in every Newton iteration.
bool all_affine(const FacetSet& facets);

/// Copy facet f of a set into fixed-size storage.
template <int Dim> Facet<Dim> gather_facet(const FacetSet& facets, local_index f);

/// Shape functions, position and tangents of a facet at one reference point.
template <int Dim> struct FacetPoint {
  NodalVector N = NodalVector::Zero();
  Eigen::Matrix<double, max_facet_nodes, Dim - 1> dN =
      Eigen::Matrix<double, max_facet_nodes, Dim - 1>::Zero();
  Eigen::Matrix<double, Dim, 1> x;
  Eigen::Matrix<double, Dim, Dim - 1> dx; ///< tangents dx/dxi (and dx/deta)
};

template <int Dim> FacetPoint<Dim> evaluate(const Facet<Dim>& facet, const double* xi);

/// Normal whose length is the surface Jacobian: 2D (t_y, -t_x) for the tangent t, 3D
/// x_xi x x_eta. It points out of the facet's body (seam::fem facet orientation).
template <int Dim>
Eigen::Matrix<double, Dim, 1> scaled_normal(const Eigen::Matrix<double, Dim, Dim - 1>& dx) {
  if constexpr (Dim == 2) {
    return {dx(1, 0), -dx(0, 0)};
  } else {
    return dx.col(0).cross(dx.col(1));
  }
}

/// Reference coordinates of the facet's centre: 0 on lines, (0,0) on quads, (1/3,1/3) on
/// triangles.
std::array<double, 2> reference_center(fem::CellType type);

/// Project p along direction d onto a line facet: xi with (x(xi) - p) x d = 0 (Newton from
/// xi0; the result reports convergence). The parameter may lie outside [-1, 1].
geometry::CurveProjection project_onto_facet(const Facet<2>& facet, const Eigen::Vector2d& p,
                                             const Eigen::Vector2d& d, double xi0 = 0.0,
                                             const geometry::NewtonOptions& options = {});

/// Project p along direction d onto a surface facet: x(xi) + alpha d = p (Newton from xi0,
/// by default the facet centre). The parameters may lie outside the reference domain.
geometry::SurfaceProjection project_onto_facet(const Facet<3>& facet, const Eigen::Vector3d& p,
                                               const Eigen::Vector3d& d, const Eigen::Vector2d& xi0,
                                               const geometry::NewtonOptions& options = {});
geometry::SurfaceProjection project_onto_facet(const Facet<3>& facet, const Eigen::Vector3d& p,
                                               const Eigen::Vector3d& d);

/// A linear piece of a facet: its 3 or 4 vertices as local node indices of the parent facet,
/// in the parent's orientation.
struct SubFacet {
  int n_vertices = 0;
  std::array<int, 4> nodes{};
};

/// The linear pieces a quadratic surface facet is split into for clipping (tri6 -> 4 tri,
/// quad8 -> 4 tri + 1 quad, quad9 -> 4 quad; ALGORITHMS.md §2); a linear facet is its own
/// single piece. Surface facets only.
std::span<const SubFacet> linear_subfacets(fem::CellType type);

} // namespace seam::mortar
