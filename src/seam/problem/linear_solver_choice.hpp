#pragma once
// `solver.linear`: which linear solver a Newton system gets, and why (the run's header).
#include "seam/io/config.hpp"
#include "seam/la/petsc.hpp"

#include <string>
#include <string_view>

namespace seam::problem {

/// `solver.linear: auto` (the default) picks GMRES + GAMG for 3D solids whose Newton system
/// is not a saddle point from `auto_iterative_dofs` dofs, and from `auto_iterative_compact_dofs`
/// if the body is compact (fewer than `auto_thin_boundary_fraction` of its nodes on the mesh's
/// boundary); MUMPS otherwise. Measured on this 2-core machine (bench/linear_solver_choice.py,
/// bench/peers/getfem/compare.py, docs/performance.md "Choosing the linear solver") since GAMG
/// gets the rigid-body modes on the condensed contact system too: on a hex8 cube pressed by a
/// rigid plane GAMG took 0.70, 0.29, 0.21, 0.12 of MUMPS's CPU time at 4.0k, 20.6k, 36.5k and
/// 59.0k dofs, on the tet10 Hertz ball 0.78, 0.57 and 0.32 at 9.8k, 21.9k and 74.0k; on the
/// thin-walled torus (68 % of the hex8 mesh's nodes and 86 % of the hex20 one's on the boundary)
/// MUMPS stayed 4.3 and 2.7 times faster at 26.4k and 49.1k dofs (20 to 400 GMRES iterations per
/// solve, against a factorization of 2e10 flops at 49.1k hex20 dofs). From 100 000 dofs MUMPS's
/// fill costs gigabytes on compact bodies, and thin ones go iterative as well. 2D systems stay
/// direct (nested dissection keeps their fill small), as do saddle points (standard
/// multipliers), on which GAMG has no smoother, and fluids (below).
inline constexpr PetscInt auto_iterative_dofs = 100000;
inline constexpr PetscInt auto_iterative_compact_dofs = 20000;
inline constexpr double auto_thin_boundary_fraction = 0.5;

/// 2D fluids stay direct at any size (bench/dfg_benchmark.py, docs/performance.md
/// "Incompressible flow: direct against iterative"): on DFG 2D-1 the fieldsplit solver
/// (BoomerAMG on the velocity block) took 2.43, 3.06, 4.96, 9.21 times MUMPS's CPU time on
/// 3.7k, 13.6k, 51.7k and 204k dofs, the ratio growing with the mesh; on 20 generalized-alpha
/// steps of DFG 2D-3 (ILU(0) on the velocity block) 0.75, 0.82, 0.98 times, rising towards 1
/// as its Krylov iterations grow (10.6, 13.6, 23.7 per Newton step), a gain within the scatter
/// of CPU times on this shared machine (some 30 %). In 3D (below) the fieldsplit was faster at
/// both sizes above 20k dofs by about 20 %, less than that scatter, but consistently, with the
/// ratio falling as the mesh grows and half of MUMPS's memory: 3D fluids from 40k dofs go
/// iterative.

/// 3D fluids of at least this many dofs take the iterative solver (bench: a steady channel
/// around a rigid flap, tet10 P2/P1, docs/fluid.md "3D"): the fieldsplit took 1.09, 0.81 and
/// 0.78 times MUMPS's CPU time on 8.3k, 22.4k and 46.0k dofs, with 18-33 FGMRES iterations
/// per Newton step, and 0.53 of its memory on 46.0k (MUMPS's fill grows faster in 3D).
inline constexpr PetscInt auto_iterative_fluid_dofs_3d = 40000;

/// What the Newton system is, as far as the choice goes. Fluid-structure interaction stays
/// direct (its fieldsplit measured slower than MUMPS, docs/fsi.md "Linear solvers").
enum class SystemKind { solid, saddle_point, fluid, fsi };

struct LinearSolverChoice {
  la::SolverKind kind;
  /// The rule that decided `auto`, e.g. "auto: 3D, 107811 dofs >= 100000"; empty when the
  /// input named the solver.
  std::string reason;
};

/// `boundary_fraction`: the share of the mesh's nodes that lie on its boundary (exterior
/// facets), which tells a thin wall (most nodes on the surface) from a compact body; it only
/// matters for 3D solids between the two thresholds.
LinearSolverChoice choose_linear_solver(io::LinearSolverKind setting, int dim, PetscInt dofs,
                                        SystemKind system, double boundary_fraction = 1.0);

/// The choice as the run's header prints it: "direct (MUMPS)", "iterative (GMRES + GAMG; auto:
/// 3D, 107811 dofs >= 100000)"; `iterative`: the name of the iterative solver.
std::string describe(const LinearSolverChoice& choice, std::string_view iterative = "GMRES + GAMG");

} // namespace seam::problem
