// `solver.linear`: the rules of `auto` (problem/linear_solver_choice.hpp) on each side of each
// rule, and the reason the run's header prints for it.
#include "seam/problem/linear_solver_choice.hpp"

#include <gtest/gtest.h>

namespace {

using seam::io::LinearSolverKind;
using seam::la::SolverKind;
using seam::problem::auto_iterative_compact_dofs;
using seam::problem::auto_iterative_dofs;
using seam::problem::auto_thin_boundary_fraction;
using seam::problem::choose_linear_solver;
using seam::problem::describe;
using seam::problem::SystemKind;

void expect_choice(int dim, PetscInt dofs, SystemKind system, SolverKind kind,
                   const std::string& reason, double boundary_fraction = 1.0) {
  const auto choice =
      choose_linear_solver(LinearSolverKind::automatic, dim, dofs, system, boundary_fraction);
  EXPECT_EQ(choice.kind, kind) << reason;
  EXPECT_EQ(choice.reason, reason);
  const std::string solver =
      kind == SolverKind::direct ? "direct (MUMPS; " : "iterative (GMRES + GAMG; ";
  EXPECT_EQ(describe(choice), solver + reason + ")");
}

TEST(LinearSolverChoice, ThreeDimensionalSolidAtTheThreshold) {
  // From 100 000 dofs every 3D solid goes iterative, thin or compact (docs/performance.md,
  // "Choosing the linear solver").
  ASSERT_EQ(auto_iterative_dofs, 100000);
  expect_choice(3, 99999, SystemKind::solid, SolverKind::direct,
                "auto: 99999 dofs < 100000, a thin body (100 % of the nodes on the boundary)");
  expect_choice(3, 100000, SystemKind::solid, SolverKind::iterative,
                "auto: 3D, 100000 dofs >= 100000");
  expect_choice(3, 107811, SystemKind::solid, SolverKind::iterative,
                "auto: 3D, 107811 dofs >= 100000", 0.9);
  expect_choice(3, 1029, SystemKind::solid, SolverKind::direct, "auto: 1029 dofs < 20000", 0.1);
}

TEST(LinearSolverChoice, CompactSolidFromTwentyThousandDofs) {
  // A compact body (the Hertz ball: 25 % of its nodes on the boundary, a cube 24 to 28 %) goes
  // iterative from 20 000 dofs; a thin wall (the torus: 68 % and 86 %) stays direct below
  // 100 000.
  ASSERT_EQ(auto_iterative_compact_dofs, 20000);
  ASSERT_EQ(auto_thin_boundary_fraction, 0.5);
  expect_choice(3, 19999, SystemKind::solid, SolverKind::direct, "auto: 19999 dofs < 20000", 0.25);
  expect_choice(3, 20000, SystemKind::solid, SolverKind::iterative,
                "auto: 3D, 20000 dofs >= 20000, 25 % of the nodes on the boundary", 0.25);
  expect_choice(3, 73977, SystemKind::solid, SolverKind::iterative,
                "auto: 3D, 73977 dofs >= 20000, 49 % of the nodes on the boundary", 0.494);
  expect_choice(3, 49104, SystemKind::solid, SolverKind::direct,
                "auto: 49104 dofs < 100000, a thin body (50 % of the nodes on the boundary)", 0.5);
  expect_choice(3, 26352, SystemKind::solid, SolverKind::direct,
                "auto: 26352 dofs < 100000, a thin body (86 % of the nodes on the boundary)", 0.86);
  // 2D and saddle points are not affected by the share.
  expect_choice(2, 50000, SystemKind::solid, SolverKind::direct, "auto: 2D", 0.1);
  expect_choice(3, 50000, SystemKind::saddle_point, SolverKind::direct, "auto: a saddle point",
                0.1);
}

TEST(LinearSolverChoice, TwoDimensionalStaysDirectAtAnySize) {
  expect_choice(2, 1000, SystemKind::solid, SolverKind::direct, "auto: 2D");
  expect_choice(2, 5000000, SystemKind::solid, SolverKind::direct, "auto: 2D");
}

TEST(LinearSolverChoice, SaddlePointStaysDirect) {
  // Standard multipliers: GAMG has no smoother for the zero block.
  expect_choice(3, 823875, SystemKind::saddle_point, SolverKind::direct, "auto: a saddle point");
  expect_choice(2, 100, SystemKind::saddle_point, SolverKind::direct, "auto: a saddle point");
}

TEST(LinearSolverChoice, FluidIsIterativeOnlyLargeIn3d) {
  // 2D fluids stay direct at any size; 3D ones from 40k dofs take the fieldsplit (measured
  // 0.78 of MUMPS's CPU time and 0.53 of its memory on 46k tet10 dofs).
  expect_choice(2, 2000000, SystemKind::fluid, SolverKind::direct, "auto: a fluid");
  expect_choice(3, 39999, SystemKind::fluid, SolverKind::direct, "auto: a fluid");
  expect_choice(3, 40000, SystemKind::fluid, SolverKind::iterative,
                "auto: a 3D fluid, 40000 dofs >= 40000");
  expect_choice(3, 2000000, SystemKind::fsi, SolverKind::direct,
                "auto: fluid-structure interaction");
}

TEST(LinearSolverChoice, NamedSolverIsTakenAsGiven) {
  for (const auto system :
       {SystemKind::solid, SystemKind::saddle_point, SystemKind::fluid, SystemKind::fsi}) {
    const auto direct = choose_linear_solver(LinearSolverKind::direct, 3, 5000000, system);
    EXPECT_EQ(direct.kind, SolverKind::direct);
    EXPECT_EQ(describe(direct), "direct (MUMPS)");
    const auto iterative = choose_linear_solver(LinearSolverKind::iterative, 2, 10, system);
    EXPECT_EQ(iterative.kind, SolverKind::iterative);
    EXPECT_EQ(describe(iterative), "iterative (GMRES + GAMG)");
  }
}

} // namespace
