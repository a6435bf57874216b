#pragma once
// Element-pair mortar integration (ALGORITHMS.md §1-§3): the contribution of one slave facet
// and one master facet to
//   D_jk = int Phi_j N~_k dA,   M_jl = int Phi_j (N_l o pi) dA,   g~_j = int Phi_j g dA,
// with g = n . (x_m - x_s) along the interpolated averaged slave normal n (g > 0 open).
// The kernels take current coordinates, so they serve the reference configuration (mesh
// tying) and any deformed one (contact) alike, and allocate nothing.
//
// With dual multipliers D is accumulated from the same products as M (the 4C practice):
// D_jj += w Phi_j N_l(xi_m), summed over l, and no off-diagonal entries. Then
// sum_k D_jk = sum_l M_jl holds to round-off whatever the quadrature error, which is the
// identity behind conservation of linear momentum (ALGORITHMS.md §7); biorthogonality makes
// the dropped off-diagonal entries zero up to quadrature error.
#include "seam/geometry/polygon.hpp"
#include "seam/geometry/projection.hpp"
#include "seam/mortar/dual_basis.hpp"
#include "seam/mortar/facet.hpp"

namespace seam::mortar {

/// The clip of mortar integration classifies and merges at round-off level, not at the
/// geometric default (1e-8 x edge). A vertex within the band of a clipping line counts as on
/// it and is kept even when it lies outside, so the clipped area, D and M jump by about
/// band x edge where a vertex crosses the band. Vertices of stuck faces that coincide in the
/// reference configuration (non-matching meshes whose nodes line up, e.g. the midside
/// sub-facet corners of quad8 faces) stay within about 1e-9 of each other for good, and
/// Newton's method stalled there at the size of the jump (a relative residual of 1e-5, the
/// iterates alternating across the band with increments of 2 x band). At 1e-13 the jump
/// lies at the residual's round-off floor; exactly coincident vertices are still merged.
inline geometry::ClipOptions mortar_clip_options() {
  geometry::ClipOptions options;
  options.merge_tolerance = 1e-13;
  return options;
}

struct PairOptions {
  geometry::ClipOptions clip = mortar_clip_options();
  geometry::NewtonOptions newton;
  /// 2D: a projected end node counts as inside a facet when its parameter is within
  /// [-1 - tol, 1 + tol] (ALGORITHMS.md §1).
  double projection_range_tolerance = 0.05;
  /// 2D pre-check: skip the pair unless the centre normals satisfy n_s . n_m < this.
  double max_normal_alignment_2d = -0.1;
  /// 3D pre-check: skip the pair if the facet centres are farther apart than this many
  /// times the longest edge of either facet.
  double max_center_distance_factor = 2.0;
  /// 3D: polynomial degree of the triangle rule per integration cell; 0 = automatic: the
  /// 7-point degree-5 rule (ALGORITHMS.md §2, step 6) when both facets are linear, degree 8
  /// when one is quadratic, which keeps Phi_j N_k of biquadratic facets exact on affine cells.
  /// The rule must not change between Newton iterations (the derivatives would not be those
  /// of the operators), so an interface chooses it once (e.g. degree 8 when it has quad4
  /// facets that are not parallelograms, is_affine).
  int cell_quadrature_degree = 0;
};

/// A slave facet ready for integration: geometry, averaged nodal normals (columns) and
/// multiplier basis.
template <int Dim> struct SlaveFacet {
  Facet<Dim> facet;
  Eigen::Matrix<double, Dim, max_facet_nodes> normals =
      Eigen::Matrix<double, Dim, max_facet_nodes>::Zero();
  SlaveBasis basis;
};

/// One pair's local blocks; rows are slave facet nodes, columns slave (D) or master (M)
/// facet nodes, all in seam::fem local order.
struct PairContribution {
  int n_slave = 0;
  int n_master = 0;
  SmallMatrix D;
  SmallMatrix M;
  NodalVector weighted_gap = NodalVector::Zero();
  /// 2D: number of segments (0 or 1); 3D: number of triangular integration cells.
  int n_cells = 0;
  /// Integrated measure: segment length (2D) or clip polygon area in the auxiliary planes (3D).
  double area = 0.0;
  /// Integration points skipped because a projection did not converge.
  int n_projection_failures = 0;
};

/// 2D segment-based integration of a line2/line3 pair (ALGORITHMS.md §1).
PairContribution integrate_pair(const SlaveFacet<2>& slave, const Facet<2>& master,
                                const PairOptions& options = {});

/// 3D integration of a surface pair via auxiliary planes, clipping and triangular cells
/// (ALGORITHMS.md §2); quadratic facets are clipped piecewise linearly and integrated with
/// their quadratic shape functions.
PairContribution integrate_pair(const SlaveFacet<3>& slave, const Facet<3>& master,
                                const PairOptions& options = {});

namespace detail {

inline PairContribution empty_contribution(int n_slave, int n_master) {
  PairContribution c;
  c.n_slave = n_slave;
  c.n_master = n_master;
  c.D = SmallMatrix::Zero(n_slave, n_slave);
  c.M = SmallMatrix::Zero(n_slave, n_master);
  return c;
}

/// Add one integration point with weight w = quadrature weight * measure, slave functions
/// N~ and Phi, master shape values Nm and gap g.
inline void accumulate_point(PairContribution& c, Multiplier multiplier, double w,
                             const NodalVector& N_tilde, const NodalVector& Phi,
                             const NodalVector& Nm, double gap) {
  for (int j = 0; j < c.n_slave; ++j) {
    const double wphi = w * Phi(j);
    if (multiplier == Multiplier::dual) {
      double row = 0.0;
      for (int l = 0; l < c.n_master; ++l) {
        const double product = wphi * Nm(l);
        c.M(j, l) += product;
        row += product;
      }
      c.D(j, j) += row;
    } else {
      for (int l = 0; l < c.n_master; ++l) c.M(j, l) += wphi * Nm(l);
      for (int k = 0; k < c.n_slave; ++k) c.D(j, k) += wphi * N_tilde(k);
    }
    c.weighted_gap(j) += wphi * gap;
  }
}

} // namespace detail

} // namespace seam::mortar
