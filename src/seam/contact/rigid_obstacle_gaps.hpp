#pragma once
// The weighted gaps of one slave facet against a rigid obstacle with their exact first and
// second derivatives: the constraint functions of energy-momentum contact against a plane, a
// sphere or a cylinder (docs/contact_dynamics.md §5).
#include <vector>

#include "seam/contact/rigid_obstacle_facet.hpp"

namespace seam::contact {

/// g~_j = int Phi_j g da of the facet's nodes j (rigid_obstacle_facet.hpp, the same kernel),
/// dg~_j/dx_v at j * nv + v and d2 g~_j/dx_v dx_w at (j * nv + v) * nv + w, nv = Dim * nodes
/// (node i, component a is variable Dim * i + a). Facets: line2, line3 (2D); tri3, quad4, tri6,
/// quad8, quad9 (3D).
template <int Dim>
void rigid_obstacle_gap_hessians(const mortar::Facet<Dim>& facet, const Obstacle& obstacle,
                                 mortar::Multiplier multiplier, std::vector<double>& gap,
                                 std::vector<double>& gradient, std::vector<double>& hessian);

} // namespace seam::contact
