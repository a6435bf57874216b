#include "seam/problem/linear_solver_choice.hpp"

namespace seam::problem {

LinearSolverChoice choose_linear_solver(io::LinearSolverKind setting, int dim, PetscInt dofs,
                                        SystemKind system) {
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
  return {la::SolverKind::direct, "auto: " + n + " dofs < " + limit};
}

std::string describe(const LinearSolverChoice& choice, std::string_view iterative) {
  std::string text = choice.kind == la::SolverKind::iterative
                         ? "iterative (" + std::string(iterative)
                         : std::string("direct (MUMPS");
  if (!choice.reason.empty()) text += "; " + choice.reason;
  return text + ")";
}

} // namespace seam::problem
