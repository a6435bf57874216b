#include "seam/problem/linear_solver_choice.hpp"

#include <cmath>

namespace seam::problem {

LinearSolverChoice choose_linear_solver(io::LinearSolverKind setting, int dim, PetscInt dofs,
                                        SystemKind system, double boundary_fraction) {
  switch (setting) {
  case io::LinearSolverKind::direct:
    return {la::SolverKind::direct, ""};
  case io::LinearSolverKind::iterative:
    return {la::SolverKind::iterative, ""};
  case io::LinearSolverKind::automatic:
    break;
  }
  // The rules in the order they are tested; the first that applies decides.
  if (system == SystemKind::fsi)
    return {la::SolverKind::direct, "auto: fluid-structure interaction"};
  if (system == SystemKind::fluid) {
    if (dim == 3 && dofs >= auto_iterative_fluid_dofs_3d)
      return {la::SolverKind::iterative, "auto: a 3D fluid, " + std::to_string(dofs) + " dofs >= " +
                                             std::to_string(auto_iterative_fluid_dofs_3d)};
    return {la::SolverKind::direct, "auto: a fluid"};
  }
  if (system == SystemKind::saddle_point) return {la::SolverKind::direct, "auto: a saddle point"};
  if (dim == 2) return {la::SolverKind::direct, "auto: 2D"};
  const auto n = std::to_string(dofs), limit = std::to_string(auto_iterative_dofs);
  if (dofs >= auto_iterative_dofs)
    return {la::SolverKind::iterative, "auto: 3D, " + n + " dofs >= " + limit};
  const auto compact = std::to_string(auto_iterative_compact_dofs);
  if (dofs < auto_iterative_compact_dofs)
    return {la::SolverKind::direct, "auto: " + n + " dofs < " + compact};
  const auto percent =
      std::to_string(static_cast<int>(std::lround(100.0 * boundary_fraction))) + " %";
  if (boundary_fraction < auto_thin_boundary_fraction)
    return {la::SolverKind::iterative, "auto: 3D, " + n + " dofs >= " + compact + ", " + percent +
                                           " of the nodes on the boundary"};
  return {la::SolverKind::direct, "auto: " + n + " dofs < " + limit + ", a thin body (" + percent +
                                      " of the nodes on the boundary)"};
}

std::string describe(const LinearSolverChoice& choice, std::string_view iterative) {
  std::string text = choice.kind == la::SolverKind::iterative
                         ? "iterative (" + std::string(iterative)
                         : std::string("direct (MUMPS");
  if (!choice.reason.empty()) text += "; " + choice.reason;
  return text + ")";
}

} // namespace seam::problem
