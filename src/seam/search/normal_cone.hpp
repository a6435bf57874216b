#pragma once
// Normal cones for self-contact pruning. A cone (axis a, half-angle t) contains every unit
// normal n with angle(n, a) <= t. If all normals of two facet groups lie within a cone of
// half-angle below alpha/2, no facet pair of the groups has normals more than alpha apart, and
// such a pair cannot be in contact when contact needs facing normals (angle > alpha, by default
// 90 degrees: outward normals of touching solid boundaries are opposed). This is the
// normal-cone test of Volino & Magnenat-Thalmann (Comput Graph Forum 13 (1994) 155) in the form
// used for contact search by Yang & Laursen (Comput Mech 41 (2008) 189): smooth patches are not
// tested against themselves.
#include "seam/common/types.hpp"

#include <array>
#include <span>

namespace seam::search {

struct NormalCone {
  std::array<double, 3> axis{0.0, 0.0, 1.0}; ///< unit vector (z = 0 in 2D)
  double angle = 0.0;                        ///< half-angle in radians, pi = all directions
};

/// Cone of the normals of one facet (line2, tri3, quad4: exact corner normals; higher-order
/// facets and facets with a zero-length normal get the full cone, which never prunes).
/// `nodes` index `coords` (dim values per node).
NormalCone facet_normal_cone(int dim, std::span<const double> coords,
                             std::span<const local_index> nodes);

/// Smallest cone about the great-circle arc between the two axes that contains both cones.
NormalCone merge(const NormalCone& a, const NormalCone& b);

/// Largest angle between a normal of cone a and a normal of cone b (an upper bound).
double max_angle_between(const NormalCone& a, const NormalCone& b);

} // namespace seam::search
