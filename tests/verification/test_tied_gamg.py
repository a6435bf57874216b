"""GMRES + GAMG on the condensed system of mesh tying (T^T K T): the tied hex/tet blocks
(examples/tied_blocks, linear elastic, one load step, `linear: iterative`).

An algebraic multigrid that sees the elasticity operator (block size 3, the six rigid-body
modes as near-null space) needs about as many iterations on a mesh twice as fine; without
them GAMG aggregates a scalar problem whose only near-null vector is the constant, and the
iterations double with each halving of the mesh size (68 at 8 divisions, 141 at 16 before
the condensed system got the bulk matrix's block size and near-null space; 29 and 33 after).
The iterations must not depend on the number of ranks either (np 4 within a factor 1.5 of
np 1). Iterations from summary.json `linear_iterations` (the GMRES iterations of all the
Newton systems of the run).
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness as H  # noqa: E402


def iterations(divisions, size, np):
    """GMRES iterations and solves of the tied blocks with `divisions` hexahedra per edge
    below and tetrahedra of `size` above."""
    work, path = H.copy_example("tied_blocks", "blocks.yaml", (
        ("model: neo_hooke", "model: linear_elastic"),
        ("steps: 5}", "steps: 1}\nsolver: {linear: iterative}")))
    geo = os.path.join(work, "blocks.geo")
    with open(geo) as f:
        text = f.read()
    for a, b in (("Transfinite Curve{1:12} = 6;", "Transfinite Curve{1:12} = %d;"
                  % (divisions + 1)), ("= 0.15;", "= %g;" % size)):
        if a not in text:
            raise AssertionError("blocks.geo: '%s' not found" % a)
        text = text.replace(a, b)
    with open(geo, "w") as f:
        f.write(text)
    out = H.solve(path, np=np)
    s = H.read_json(os.path.join(out, "summary.json"))
    H.cleanup(work, out)
    if s["status"] != "converged":
        raise AssertionError("%d divisions, np %d: %s" % (divisions, np, s["status"]))
    print("   %d divisions, %d dofs, np %d: %d GMRES iterations in %d solves"
          % (divisions, s["dofs"], np, s["linear_iterations"], s["linear_solves"]))
    return s["linear_iterations"], s["linear_solves"]


def test_iterations_independent_of_mesh_and_ranks():
    coarse, solves = iterations(8, 0.15, 1)
    fine, fine_solves = iterations(16, 0.075, 1)
    coarse_np4, solves_np4 = iterations(8, 0.15, 4)
    if solves != fine_solves or solves != solves_np4:
        raise AssertionError("linear solves differ: %d, %d, %d" % (solves, fine_solves,
                                                                    solves_np4))
    if fine > 1.3 * coarse:
        raise AssertionError("GMRES iterations grow from %d to %d when the mesh size halves "
                             "(at most a factor 1.3)" % (coarse, fine))
    if not coarse / 1.5 <= coarse_np4 <= 1.5 * coarse:
        raise AssertionError("GMRES iterations at np 4: %d, at np 1: %d (within a factor 1.5)"
                             % (coarse_np4, coarse))


if __name__ == "__main__":
    H.main([test_iterations_independent_of_mesh_and_ranks])
