#pragma once
// Errors of the discrete displacement against an exact solution given in the input
// (output.exact_displacement): the L2 norm and the H1 seminorm over the whole mesh. This is
// how a user verifies a model by the method of manufactured solutions.
#include "seam/io/expression.hpp"
#include "seam/la/petsc.hpp"
#include "seam/problem/discretization.hpp"

#include <vector>

namespace seam::problem {

struct ErrorNorms {
  double l2 = 0.0;       ///< ||u_h - u||_L2
  double h1_semi = 0.0;  ///< |u_h - u|_H1 = ||grad(u_h - u)||_L2
  double l2_exact = 0.0; ///< ||u||_L2, for relative errors
};

/// Integrates over this rank's cells with a rule two degrees above the stiffness rule and sums
/// over ranks (collective). The exact gradient is taken by central differences of the
/// expressions (step 1e-6 of the cell size), accurate far beyond discretization errors.
ErrorNorms error_norms(const Discretization& disc, const la::Vector& u, double t,
                       const std::vector<io::Expression>& exact);

} // namespace seam::problem
