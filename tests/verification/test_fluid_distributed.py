"""Fluid runs on the distributed mesh (issues 12 and 14): each rank holds its cells, their
nodes and one ghost layer, as the solids do (docs/parallel.md); the moving mesh (ALE) is
solved distributed, and tied fluid subdomains use the distributed condensed tying.

  * DFG 2D-1 (coarse, Taylor-Hood, MUMPS): forces.csv and the probes' pressure difference on
    3 ranks equal those on 1 rank to 1e-10 relative (forces relative to the size of the
    force), and the run does not announce a replicated mesh.
  * Generalized-alpha on a moving mesh (test_ale.py's free-stream case, Q2/Q1 and P1/P1,
    with a force group on the walls): every step's forces on 3 ranks equal 1 rank to 1e-10,
    and the free stream stays uniform to 1e-12 on both.
  * Tied fluid subdomains (test_fluid_tying.py's Poiseuille flow across a non-matching
    interface, tri6, quad9 and tet10): the wall forces on 3 ranks equal 1 rank to 1e-10 and
    the flow stays exact.
  * No rank holds the whole mesh at np = 3 (the solids' test_held_cells_np3 pattern): on a
    finer DFG 2D-1 mesh, every rank holds at most 1.1 x (its cells + the ghost layer found by
    brute force from the written pieces) cells, fewer than 0.6 of the mesh, the owned nodes
    add up to the mesh's, and the pieces hold every cell once.
  * An enclosed flow (driven cavity): the pinned pressure level, probes and forces on 3 ranks
    equal 1 rank to 1e-10.
Restarts of fluid runs 1 -> 3 (fixed, tied and moving meshes): test_restart.py.
"""
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import geometry  # noqa: E402
import harness as H  # noqa: E402
import test_ale as A  # noqa: E402
import test_fluid as F  # noqa: E402
import test_fluid_tying as FT  # noqa: E402
import vtu_reader  # noqa: E402

_dirs = []
REPLICATED = "every rank holds the whole mesh"


def run(work, np):
    """Runs case.yaml in `work` on np ranks: the output directory and seam's stdout."""
    out = tempfile.mkdtemp(prefix="seam_dfluid_")
    _dirs.append(out)
    _, stdout, _ = H.run(["run", os.path.join(work, "case.yaml"), "-o", out], np=np)
    if REPLICATED in stdout:
        raise AssertionError("np %d: the run keeps a replicated mesh:\n%s" % (np, stdout))
    return out


def dfg_case(h, hc):
    work = tempfile.mkdtemp(prefix="seam_dfluid_dfg_")
    _dirs.append(work)
    with open(os.path.join(F.EXAMPLE, "dfg.geo")) as f:
        geo = f.read()
    for a, b in (("DefineNumber[0.04,", "DefineNumber[%g," % h),
                 ("DefineNumber[0.006,", "DefineNumber[%g," % hc)):
        if a not in geo:
            raise AssertionError("dfg.geo: '%s' not found" % a)
        geo = geo.replace(a, b)
    H.write_case(work, "dfg.geo", geo)
    with open(os.path.join(F.EXAMPLE, "dfg_2d1.yaml")) as f:
        H.write_case(work, "case.yaml", f.read())
    return work


def compare_forces(one, three, rtol, what, scale=0.0):
    """forces.csv rows of 1 and 3 ranks: the same steps and groups, each component equal to
    rtol times the size of its force, or of `scale` where the force is smaller (a force that
    is zero in exact arithmetic is round-off, whose digits depend on the summation order).
    Returns the largest relative difference."""
    a = H.read_csv(os.path.join(one, "forces.csv"))
    b = H.read_csv(os.path.join(three, "forces.csv"))
    if len(a) != len(b) or not a:
        raise AssertionError("%s: %d and %d rows in forces.csv" % (what, len(a), len(b)))
    worst = 0.0
    for x, y in zip(a, b):
        if (x["step"], x["name"]) != (y["step"], y["name"]):
            raise AssertionError("%s: rows %s and %s differ" % (what, x, y))
        size = max([scale] + [abs(x[k]) for k in ("fx", "fy", "fz")])
        for k in ("fx", "fy", "fz"):
            d = abs(x[k] - y[k]) / size if size > 0 else abs(y[k])
            worst = max(worst, d)
            if d > rtol:
                raise AssertionError("%s: step %d %s %s: %.15g on 1 rank, %.15g on 3"
                                     % (what, x["step"], x["name"], k, x[k], y[k]))
    print("   %s: %d force rows, largest relative difference 1 -> 3 ranks %.2e"
          % (what, len(a), worst))
    return worst


def test_dfg_2d1_forces_np3():
    work = dfg_case(0.08, 0.012)
    one, three = run(work, 1), run(work, 3)
    compare_forces(one, three, 1e-10, "DFG 2D-1 coarse")
    dp = []
    for out in (one, three):
        probes = H.last_step_rows(H.read_csv(os.path.join(out, "probes.csv")))
        dp.append(probes[0]["pressure"] - probes[1]["pressure"])
    H.assert_close(dp[1], dp[0], rtol=1e-10, what="pressure difference on 3 ranks")
    H.assert_close(dp[0], F.DP_REF, rtol=5e-3, what="pressure difference")
    H.cleanup(*_dirs)


def test_free_stream_np3():
    for kind, order in (("quad_structured", 2), ("tri", 1)):
        work = tempfile.mkdtemp(prefix="seam_dfluid_ale_")
        _dirs.append(work)
        H.write_case(work, "body.geo", geometry.rectangle(kind, 0.25 if order == 2 else 0.2,
                                                          order))
        u = "[1, 0.5]"
        text = A.FREE_STREAM % dict(
            dim=2, order=order, motion=A.MOTION_2D, u=u, probe="[1.1, 0.45]",
            walls="".join("  - {region: %s, type: velocity, value: %s}\n" % (w, u)
                          for w in ("left", "top", "bottom")))
        text += "  forces: [{name: walls, regions: [left, top, bottom]}]\n"
        H.write_case(work, "case.yaml", text)
        outs = [run(work, np) for np in (1, 3)]
        for out in outs:
            errors = H.read_csv(os.path.join(out, "errors.csv"))
            worst = max(max(e["velocity_l2_error"], e["pressure_l2_error"]) for e in errors)
            if len(errors) != 8 or worst > 1e-12:
                raise AssertionError("%s: the free stream is not preserved: %s" % (kind, errors))
        # The exact force is zero: compare at the scale of the flow's dynamic pressure
        # rho |u|^2 / 2 times the walls' length, about 1.
        compare_forces(outs[0], outs[1], 1e-10, "free stream, moving %s mesh, order %d"
                       % (kind, order), scale=1.0)
    H.cleanup(*_dirs)


def test_tied_np3():
    tet = FT.TIED_POISEUILLE_3D + "  forces: [{name: walls, regions: [left, right]}]\n"
    for kind, geo, text in (
            ("tri", geometry.tied_rectangles(0.25, 0.2, order=2, kind="tri"), FT.TIED_POISEUILLE),
            ("quad", geometry.tied_rectangles(0.25, 0.2, order=2, kind="quad"),
             FT.TIED_POISEUILLE),
            ("tet", geometry.tied_boxes(0.5, 0.4, order=2, kind="tet"), tet)):
        work = tempfile.mkdtemp(prefix="seam_dfluid_tied_")
        _dirs.append(work)
        H.write_case(work, "body.geo", geo)
        H.write_case(work, "case.yaml", text)
        outs = [run(work, np) for np in (1, 3)]
        for out in outs:
            err = H.read_csv(os.path.join(out, "errors.csv"))[-1]
            if err["velocity_l2_error"] > 1e-10 or err["pressure_l2_error"] > 1e-10:
                raise AssertionError("%s: Poiseuille flow across the tied interface is not "
                                     "exact: %s" % (kind, err))
        compare_forces(outs[0], outs[1], 1e-10, "tied Poiseuille flow, %s" % kind)
    H.cleanup(*_dirs)


CAVITY = """\
dimension: 2
mesh: {geo: body.geo, order: 2}
materials: {oil: {model: newtonian_fluid, density: 1, viscosity: 0.01}}
bodies: [{region: body, material: oil}]
boundary_conditions:
  - {region: left, type: velocity, value: [0, 0]}
  - {region: right, type: velocity, value: [0, 0]}
  - {region: bottom, type: velocity, value: [0, 0]}
  - {region: top, type: velocity, value: ["16*x*x*(2-x)*(2-x)/16", 0]}
time: {integrator: static, end: 1, steps: 1}
output:
  probes: [[0.5, 0.5], [1.5, 0.9]]
  forces: [{name: lid, regions: [top]}, {name: floor, regions: [bottom]}]
"""


def test_enclosed_flow_np3():
    """A driven cavity (every wall's velocity given): the pressure is pinned at the vertex
    with the lowest id of the mesh as read, so its level, and the forces, are the same on 3
    ranks as on 1 (pinned at the lowest global dof, it depended on the partition)."""
    work = tempfile.mkdtemp(prefix="seam_dfluid_cavity_")
    _dirs.append(work)
    H.write_case(work, "body.geo", geometry.rectangle("tri", 0.2, 2))
    H.write_case(work, "case.yaml", CAVITY)
    outs = [run(work, np) for np in (1, 3)]
    compare_forces(outs[0], outs[1], 1e-10, "driven cavity")
    p = [H.last_step_rows(H.read_csv(os.path.join(out, "probes.csv"))) for out in outs]
    for a, b in zip(p[0], p[1]):
        H.assert_close(b["pressure"], a["pressure"], rtol=1e-10, atol=1e-12 * abs(a["vx"]),
                       what="probe pressure on 3 ranks")
    print("   probe pressures %.12f, %.12f on both" % (p[0][0]["pressure"], p[0][1]["pressure"]))
    H.cleanup(*_dirs)


def piece_cells(pvtu):
    """Per piece of a .pvtu, its cells as sets of node positions (rounded)."""
    return [[frozenset(tuple(round(v, 9) for v in piece["points"][i]) for i in cell)
             for cell in piece["cells"]] for piece in vtu_reader.read_pieces(pvtu)]


def test_held_cells_np3():
    out = run(dfg_case(0.04, 0.006), 3)
    summary = H.read_json(os.path.join(out, "summary.json"))
    detail = summary["ranks_detail"]
    cells = piece_cells(os.path.join(out, "results_00001.pvtu"))
    if len(cells) != 3 or len(detail) != 3:
        raise AssertionError("%d pieces, %d ranks_detail entries" % (len(cells), len(detail)))
    total = sum(len(part) for part in cells)
    if total != summary["cells"] or len(set().union(*[set(p) for p in cells])) != total:
        raise AssertionError("pieces hold %d cells (%d distinct), the mesh %d"
                             % (total, len(set().union(*[set(p) for p in cells])),
                                summary["cells"]))
    if sum(r["owned_nodes"] for r in detail) != summary["nodes"]:
        raise AssertionError("owned nodes add up to %d, the mesh has %d"
                             % (sum(r["owned_nodes"] for r in detail), summary["nodes"]))
    for r, part in enumerate(cells):
        d = detail[r]
        mine = set().union(*part)
        ghosts = [c for q, other in enumerate(cells) if q != r for c in other if c & mine]
        held = d["cells"] + d["ghost_cells"]
        print("   rank %d: owns %d cells, holds %d (ghost layer by brute force %d); nodes held "
              "%d, owned %d + ghost %d; mesh %d cells, %d nodes"
              % (r, d["cells"], held, len(ghosts), d["nodes"], d["owned_nodes"],
                 d["ghost_nodes"], summary["cells"], summary["nodes"]))
        if d["cells"] != len(part):
            raise AssertionError("rank %d assembles %d cells, its piece has %d"
                                 % (r, d["cells"], len(part)))
        if held > 1.1 * (len(part) + len(ghosts)):
            raise AssertionError("rank %d holds %d cells, more than 1.1 x (%d own + %d ghosts)"
                                 % (r, held, len(part), len(ghosts)))
        if held > 0.6 * summary["cells"] or d["nodes"] > 0.6 * summary["nodes"]:
            raise AssertionError("rank %d holds %d of %d cells and %d of %d nodes"
                                 % (r, held, summary["cells"], d["nodes"], summary["nodes"]))
        if d["owned_nodes"] + d["ghost_nodes"] > d["nodes"]:
            raise AssertionError("rank %d: owned + ghost nodes exceed the nodes it holds" % r)
    H.cleanup(*_dirs)


if __name__ == "__main__":
    H.main([test_dfg_2d1_forces_np3, test_free_stream_np3, test_tied_np3, test_enclosed_flow_np3,
            test_held_cells_np3])
