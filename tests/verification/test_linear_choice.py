"""`solver.linear: auto` on real meshes (problem/linear_solver_choice.hpp): a 3D solid goes to
GMRES + GAMG from 100 000 dofs, and from 20 000 dofs if it is compact, that is if fewer than
half of its nodes lie on the mesh's boundary; thin walls (most nodes on the surface, where GAMG
converged slowly: docs/performance.md, "Choosing the linear solver") and smaller problems keep
MUMPS.

Structured hex8 boxes of nx x ny x nz cells, whose boundary nodes are counted exactly:
(nx+1)(ny+1)(nz+1) - (nx-1)(ny-1)(nz-1). A 20^3 cube (27,783 dofs, 25.9 % on the boundary)
must go iterative, on 1 and on 3 ranks with the same share; a 60 x 60 x 1 plate (22,326 dofs,
every node on the boundary) and a 17^3 cube (17,496 dofs, below 20 000) must stay direct. The
run's header line `linear solver: ...` says which and why.
"""
import os
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness as H  # noqa: E402

GEO = """Point(1) = {0, 0, 0, 1};
l[] = Extrude {%g, 0, 0} {Point{1}; Layers{%d};};
s[] = Extrude {0, %g, 0} {Line{l[1]}; Layers{%d}; Recombine;};
v[] = Extrude {0, 0, %g} {Surface{s[1]}; Layers{%d}; Recombine;};
Physical Volume("body") = {v[1]};
Physical Surface("bottom") = {s[1]};
Physical Surface("top") = {v[0]};
"""

YAML = """dimension: 3
mesh: {geo: box.geo}
materials:
  m: {model: linear_elastic, young: 100, poisson: 0.3}
bodies:
  - {region: body, material: m}
boundary_conditions:
  - {region: bottom, type: dirichlet, components: [x, y, z], value: [0, 0, 0]}
  - {region: top, type: dirichlet, components: [z], value: ["-0.001*t"]}
time: {integrator: static, end: 1, steps: 1}
"""


def header(n, size, np=1):
    """The `linear solver:` line of a run on an n = (nx, ny, nz) box of the given size."""
    work = tempfile.mkdtemp(prefix="seam_linear_choice_")
    try:
        H.write_case(work, "box.geo", GEO % (size[0], n[0], size[1], n[1], size[2], n[2]))
        H.write_case(work, "box.yaml", YAML)
        _, out, _ = H.run(["run", "box.yaml", "-o", "out"], np=np, cwd=work)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    lines = [l.strip() for l in out.splitlines() if l.strip().startswith("linear solver: ")]
    if len(lines) != 1:
        raise AssertionError("expected one 'linear solver: ...' line, got %s" % lines)
    return lines[0][len("linear solver: "):]


def expected(n):
    nodes = (n[0] + 1) * (n[1] + 1) * (n[2] + 1)
    inner = max(n[0] - 1, 0) * max(n[1] - 1, 0) * max(n[2] - 1, 0)
    return 3 * nodes, round(100.0 * (nodes - inner) / nodes)


def expect(line, want):
    if line != want:
        raise AssertionError("linear solver: %r\n          expected %r" % (line, want))


def test_compact_cube_goes_iterative():
    n = (20, 20, 20)
    dofs, percent = expected(n)
    want = ("iterative (GMRES + GAMG; auto: 3D, %d dofs >= 20000, %d %% of the nodes on the "
            "boundary)" % (dofs, percent))
    expect(header(n, (1, 1, 1)), want)
    # Each rank counts the boundary nodes it owns (its ghost layer holds every cell around
    # them): the share over all ranks must be the same.
    expect(header(n, (1, 1, 1), np=3), want)


def test_thin_plate_stays_direct():
    n = (60, 60, 1)
    dofs, percent = expected(n)
    assert percent == 100
    expect(header(n, (1, 1, 0.01)),
           "direct (MUMPS; auto: %d dofs < 100000, a thin body (100 %% of the nodes on the "
           "boundary))" % dofs)


def test_small_cube_stays_direct():
    n = (17, 17, 17)
    dofs, _ = expected(n)
    expect(header(n, (1, 1, 1)), "direct (MUMPS; auto: %d dofs < 20000)" % dofs)


if __name__ == "__main__":
    H.main([test_compact_cube_goes_iterative, test_thin_plate_stays_direct,
            test_small_cube_stays_direct])
