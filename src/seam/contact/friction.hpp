#pragma once
// The frictional complementarity condition of one slave node (ALGORITHMS.md §5 and §9;
// Hueeber, Stadler & Wohlmuth 2008; Gitterle, Popp, Gee & Wall 2010), in the form the
// semi-smooth Newton method linearizes.
//
// A node carries a Cartesian multiplier lambda (its contact force on the slave side is
// D_jj lambda, the traction on the slave body is -lambda), the averaged unit normal n, the
// weighted slip increment u~ of the step (Gitterle et al. 2010, eq. 31: built from D and M of
// the current and of the last converged configuration, so that rigid motions give none), D_jj
// and the weighted gap g~. With P = I - n n^T, the nodal slip s = u~ / D_jj and gap g = g~ / D_jj:
//   lambda_n = n . lambda,  lambda_t = P lambda,  z = lambda_t + c_t P s,
//   xi = mu (lambda_n - c_n g)   (Coulomb)   or   xi = S   (Tresca),
//   stick if |z| <= xi:   C_t = c_t P s = 0                 (no slip in the step),
//   slip otherwise:       C_t = lambda_t - xi z / |z| = 0    (|lambda_t| = xi along the slip).
// This is Hueeber's NCP max(xi, |z|) lambda_t - xi z = 0 divided by max(xi, |z|): the slip
// residual never subtracts two large, nearly equal products.
//
// C_t lies in the tangent plane; the solver enforces its components along the tangents t of
// the node (t . n = 0) and needs their exact derivatives. friction_row returns them as
//   d(t . C_t) = alpha . dlambda + a_n . dn + a_u . du~ + a_D dD_jj + a_g dg~
// with n, u~, D_jj and g~ treated as independent inputs (the caller chains in their
// derivatives with respect to the displacements).
#include "seam/io/config.hpp"

#include <array>

namespace seam::contact {

/// Status of a slave node; the values are those of the VTU field contact_status.
enum class NodeStatus : char { inactive = 0, stick = 1, slip = 2 };

struct FrictionLaw {
  io::FrictionModel model = io::FrictionModel::frictionless;
  double mu = 0.0;    ///< Coulomb coefficient
  double bound = 0.0; ///< Tresca bound
  double c_n = 1.0;
  double c_t = 1.0;
  /// Gap below which a node counts as touching (as in the normal active set): the stick/slip
  /// decision compares |z| with mu (lambda_n - c_n (g - touching)), so that a touching node
  /// without pressure starts in stick instead of sliding freely (the slip condition itself
  /// keeps the exact bound).
  double touching = 0.0;
};

/// The nodal quantities the condition depends on (first dim entries of the vectors).
struct FrictionNode {
  int dim = 3;
  std::array<double, 3> lambda{};
  std::array<double, 3> normal{};
  std::array<double, 3> slip{}; ///< weighted slip increment u~
  double D = 1.0;
  double weighted_gap = 0.0;
};

/// The slip bound xi (>= 0) of an active node.
double slip_bound(const FrictionLaw& law, const FrictionNode& node);
/// Stick or slip for an active node.
NodeStatus stick_or_slip(const FrictionLaw& law, const FrictionNode& node);

/// Whether `status` (stick or slip) satisfies the stick/slip decision up to `tolerance` (in
/// traction units): a node on the boundary of the cone may be either.
bool admissible(const FrictionLaw& law, const FrictionNode& node, NodeStatus status,
                double tolerance);

/// t . C_t and its derivative coefficients for an active node in status `status`.
struct FrictionRow {
  double value = 0.0;
  std::array<double, 3> alpha{}, a_n{}, a_u{};
  double a_D = 0.0;
  double a_g = 0.0;
};
FrictionRow friction_row(const FrictionLaw& law, const FrictionNode& node, NodeStatus status,
                         const std::array<double, 3>& tangent);

} // namespace seam::contact
