"""Saddle points with `solver.linear: iterative` (docs/input.md, "Linear solver"): FGMRES with
a Schur fieldsplit (GAMG with the rigid-body modes on the displacements, the selfp
approximation S = E - C diag(K)^-1 B^T on the multipliers) solves the systems [K B^T; C E] of
contact with standard multipliers and of saddle-point mesh tying. The Krylov solve stops at the
inexact-Newton forcing of the iterative path, which keeps Newton's convergence: each case
needs the same number of Newton iterations per step as MUMPS (within one) and gives the same
reactions to 1e-8 of the largest, on 1 and on 3 ranks (Coulomb friction, whose multipliers
have normal and tangential components, on one). GMRES + GAMG on the whole indefinite
matrix failed every solve of the Hertz case ("the linear solver failed", five step cuts).
"""
import csv
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness as H  # noqa: E402
import test_distribution as D  # noqa: E402

LINEAR = (("time:", "solver: {linear: %s}\ntime:"),)


def hertz_case(linear):
    """The sphere pressed onto the block (examples/hertz_3d/sphere_block.yaml, 6099 dofs) with
    standard multipliers, two load steps."""
    _, path = H.copy_example("hertz_3d", "sphere_block.yaml", (
        ("multiplier: dual", "multiplier: standard"),
        ("steps: 5}", "steps: 2}"),
        ("  newton:", "  linear: %s\n  newton:" % linear)))
    return path


def tied_case(linear):
    """The tied blocks stretched to 3 x 1 x 1 (test_distribution.wide_tied_case) with
    saddle-point tying."""
    return D.wide_tied_case(D.SADDLE_POINT + tuple((a, b % linear) for a, b in LINEAR))


def rows(out, name):
    with open(os.path.join(out, name)) as f:
        return list(csv.DictReader(f))


def compare(case, nps=(1, 3)):
    for np in nps:
        outs = {lin: H.solve(case(lin), np=np) for lin in ("direct", "iterative")}
        steps = {lin: [int(r["newton_iterations"]) for r in rows(o, "steps.csv")]
                 for lin, o in outs.items()}
        if len(steps["direct"]) != len(steps["iterative"]) or any(
                abs(a - b) > 1 for a, b in zip(steps["direct"], steps["iterative"])):
            raise AssertionError("np %d: Newton iterations per step: direct %s, iterative %s"
                                 % (np, steps["direct"], steps["iterative"]))
        forces = {lin: [float(r[c]) for r in rows(o, "reactions.csv") for c in ("fx", "fy", "fz")]
                  for lin, o in outs.items()}
        scale = max(abs(v) for v in forces["direct"])
        error = max(abs(a - b) for a, b in zip(forces["direct"], forces["iterative"])) / scale
        if len(forces["direct"]) != len(forces["iterative"]) or error > 1e-8:
            raise AssertionError("np %d: reactions differ by %.3g of the largest" % (np, error))
        print("  np %d: Newton iterations %s (both), reactions within %.2g" %
              (np, steps["direct"], error))


def test_hertz_standard_multipliers():
    compare(hertz_case)


def test_saddle_point_tying():
    compare(tied_case)


def friction_case(linear):
    """Cattaneo-Mindlin (examples/cattaneo_mindlin/cattaneo.yaml, 2D, Coulomb friction) with
    standard multipliers: normal and tangential multipliers per slave node."""
    _, path = H.copy_example("cattaneo_mindlin", "cattaneo.yaml", (
        ("    friction: {model: coulomb, coefficient: 0.3}",
         "    friction: {model: coulomb, coefficient: 0.3}\n    multiplier: standard"),
        ("  newton:", "  linear: %s\n  newton:" % linear)))
    return path


def test_friction_standard_multipliers():
    compare(friction_case, nps=(1,))


if __name__ == "__main__":
    H.main([test_hertz_standard_multipliers, test_saddle_point_tying,
            test_friction_standard_multipliers])
