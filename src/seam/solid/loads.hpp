#pragma once
// External loads: follower pressure and dead traction on boundary facets, body force on cells.
//
// Every kernel here returns its contribution to the residual r = f_int - f_ext, i.e. MINUS the
// external force, and (where it depends on u) the derivative of that contribution, so callers
// add everything into r and K alike. Outputs are overwritten. Layouts as in element.hpp.
#include "seam/fem/cell.hpp"
#include "seam/solid/element.hpp"

#include <functional>
#include <span>

namespace seam::solid {

/// Scalar field of the reference position X (dim values), e.g. a pressure p(X, t) with t bound.
using ScalarField = std::function<double(const double* X)>;
/// Vector field of the reference position X: writes dim values to `value`.
using VectorField = std::function<void(const double* X, double* value)>;

/// One boundary facet: line2/line3 in 2D, tri3/tri6/quad4/quad8/quad9 in 3D, with its nodes in
/// the order of fem::facet_nodes so that its parametrisation gives the outward normal.
struct FacetInput {
  fem::CellType facet = fem::CellType::quad4;
  int dim = 3;               ///< spatial dimension = fem::dimension(facet) + 1
  std::span<const double> X; ///< reference coordinates, n_nodes * dim
  std::span<const double> u; ///< displacements, n_nodes * dim (may be empty for dead loads)
  int quadrature_degree = 0; ///< <= 0: fem::default_quadrature_degree(facet)
};

/// Follower pressure p (positive pushes into the body): the force density is -p n da with n
/// the outward normal of the current configuration, so the residual contribution is
///   r_a = + int p(X) N_a n da = + int p N_a (x,xi x x,eta) dxi deta      (3D)
///   r_a = + int p(X) N_a (x,xi_y, -x,xi_x) dxi                            (2D)
/// and K_ab = dr_a/du_b (nonsymmetric; skipped if K is empty). p is evaluated at the
/// reference position of each quadrature point.
void follower_pressure(const FacetInput& in, const ScalarField& p, std::span<double> r,
                       std::span<double> K);
/// The same with a constant pressure.
void follower_pressure(const FacetInput& in, double p, std::span<double> r, std::span<double> K);

/// Dead traction t(X) per unit reference area (dim values): r_a = - int N_a t dA.
/// The displacement in `in` is not used.
void dead_traction(const FacetInput& in, const VectorField& t, std::span<double> r);

/// Body force b(X) per unit reference volume (dim values) on a solid cell: r_a = - int N_a b dV.
/// The displacement and material of `in` are not used; degree <= 0 means
/// fem::default_quadrature_degree(cell).
KernelStatus body_force(const ElementInput& in, const VectorField& b, std::span<double> r);

} // namespace seam::solid
