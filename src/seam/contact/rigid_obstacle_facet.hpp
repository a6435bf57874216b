#pragma once
// The mortar quantities of one slave facet against a rigid obstacle (plane, sphere, cylinder;
// rigid_obstacle.hpp), integrated over the whole facet with the facet's own Gauss rule
// (element-based integration). The analytic surface covers every slave facet near it, so no
// segmentation is needed: the gap at a point x of the facet is its signed distance g(x) to the
// obstacle's surface (n . (x - p) for a plane, |x - c| - R for a sphere), and
//   D_jk = int Phi_j N~_k da,   g~_j = int Phi_j g da
// with the rule the dual basis Phi is built with. D and g~ are then exact also on quad4 facets
// that are not parallelograms, where the triangles of a clip polygon integrate the non-polynomial
// integrands only approximately (Puso & Laursen 2004), and biorthogonality holds to round-off:
// the contact patch test passes on any mesh. Derivatives with respect to the facet's nodal
// coordinates come from forward-mode dual numbers over the same kernel.
#include <array>
#include <vector>

#include "seam/contact/rigid_obstacle.hpp"
#include "seam/mortar/dual_basis.hpp"
#include "seam/mortar/facet.hpp"

namespace seam::contact {

struct RigidObstacleFacet {
  int n = 0;           ///< nodes of the facet
  int n_variables = 0; ///< dim * n with derivatives, 0 without
  /// D_jk at j * n + k (N~: the modified basis of tri6/quad8 with dual multipliers).
  std::array<double, mortar::max_facet_nodes * mortar::max_facet_nodes> D{};
  std::array<double, mortar::max_facet_nodes> gap{}; ///< g~_j
  double area = 0.0;
  /// dD_jk / dx_v at (j * n + k) * n_variables + v, dg~_j / dx_v at j * n_variables + v; node i
  /// component a of the facet is variable dim * i + a.
  std::vector<double> dD, dgap;
};

/// `obstacle`: its surface in the current configuration.
template <int Dim>
void rigid_obstacle_facet(const mortar::Facet<Dim>& facet, const Obstacle& obstacle,
                          mortar::Multiplier multiplier, bool derivatives, RigidObstacleFacet& out);

} // namespace seam::contact
