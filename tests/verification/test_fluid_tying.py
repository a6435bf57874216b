"""Mortar mesh tying of fluid subdomains (issue 14): the velocity of two fluid bodies tied
across non-matching meshes with dual multipliers, condensed as for solids; the pressure of
each side is its own (docs/fluid.md, "Mesh tying of fluid subdomains").

  * Poiseuille flow crossing the tied interface: two unit squares stacked in y, meshed
    independently (h 0.25 below, 0.2 above), flow u = (0, 4 x (1 - x)) upwards, walls at
    x = 0 and 1, do-nothing outflow: the exact velocity is quadratic along the interface, in
    the slave trace space, and the pressure 8 mu (2 - y) is linear, so the discrete solution
    is exact (L2 errors < 1e-10) on quad9 and tri6, and equal on 3 ranks.
  * DFG 2D-1 on the channel cut at x = 0.6 into two meshes that do not match there (different
    numbers of cells on the two sides of the cut): c_D and c_L within 0.1 % of the uncut mesh
    of the same cell sizes, and the cut mesh's values on 3 ranks equal to 1 rank.
  * 3D: the plane Poiseuille flow through two cubes tied non-matching, exact on tet10 and
    hex27; stabilized linear cells tied keep a uniform flow uniform.
  * Moving meshes (ALE): the tied interface moves with the mesh, its mortar operators
    integrated again in the configuration of every step. A uniform flow (0.3, 1) through the
    two non-matching meshes of the Poiseuille case moved by a smooth prescribed motion of every
    node (interface and boundary included; generalized-alpha, 8 steps), or by the pseudo-elastic
    mesh with mesh_displacement conditions on the outflow and on both sides of the interface,
    stays uniform: velocity L2 errors < 1e-12 at every step (measured 3e-16), pressure < 1e-11
    (measured 7.0e-13 at the first step, falling: the rates of the conditions at t = 0 are
    finite differences in time).
    The Poiseuille flow on the two meshes translating at V = (0.3, 0.2), the conditions and
    initial velocity shifted by V (Galilean invariance: u = (0.3, 0.2 + 4 x'(1 - x')),
    p = 0.8 (2 - y') in the coordinates x' = x - V t moving with the mesh) stays exact (L2
    errors < 1e-10; measured 5e-15 and 5e-12) with the wall force of the fixed mesh. Quad9 and
    tri6 on 1 rank, tri6 on 3 ranks.
  * PCD (`-fluid_schur pcd`) with the tied subdomains: the Poiseuille flow stays exact and the
    cut DFG 2D-1 gives MUMPS's forces to 1e-8, on 1 and 3 ranks (with the tied sides left
    natural in A_p, the downstream subdomain's A_p is singular and the cut DFG 2D-1 fails).
  * Bad input: contact between fluids, standard multipliers.
"""
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import geometry  # noqa: E402
import harness as H  # noqa: E402
import test_fluid as F  # noqa: E402

TIED_POISEUILLE = """\
dimension: 2
mesh: {geo: body.geo, order: 2}
materials: {oil: {model: newtonian_fluid, density: 1, viscosity: 0.1}}
bodies: [{region: lower, material: oil}, {region: upper, material: oil}]
boundary_conditions:
  - {region: bottom, type: velocity, value: [0, "4*x*(1-x)"]}
  - {region: left, type: velocity, value: [0, 0]}
  - {region: right, type: velocity, value: [0, 0]}
interfaces:
  - {name: cut, type: mesh_tying, slave: upper_bottom, master: lower_top}
time: {integrator: static, end: 1, steps: 1}
output:
  probes: [[0.3, 1.0], [0.7, 1.5]]
  forces: [{name: walls, regions: [left, right]}]
  exact_velocity: [0, "4*x*(1-x)"]
  exact_pressure: "0.8*(2-y)"
"""


def tied_poiseuille(kind, np=1, solver=None, options=(), summary=None):
    """`solver`: the `solver` section, if given; `options`: PETSc options after `--`; a dict
    `summary` is updated with summary.json."""
    work = tempfile.mkdtemp(prefix="seam_fluid_tied_")
    H.write_case(work, "body.geo", geometry.tied_rectangles(0.25, 0.2, order=2, kind=kind))
    text = TIED_POISEUILLE + ("solver: %s\n" % solver if solver else "")
    out = H.solve(H.write_case(work, "case.yaml", text), np=np,
                  extra=["--"] + list(options) if options else ())
    err = H.read_csv(os.path.join(out, "errors.csv"))[-1]
    force = H.read_csv(os.path.join(out, "forces.csv"))[-1]
    if summary is not None:
        summary.update(H.read_json(os.path.join(out, "summary.json")))
    H.cleanup(work, out)
    print("   %s, np %d%s: velocity L2 %.2e, pressure L2 %.2e, wall force y %.12f"
          % (kind, np, ", " + " ".join(options) if options else "", err["velocity_l2_error"],
             err["pressure_l2_error"], force["fy"]))
    if err["velocity_l2_error"] > 1e-10 or err["pressure_l2_error"] > 1e-10:
        raise AssertionError("Poiseuille flow across the tied interface is not exact: %s" % err)
    return force


def test_poiseuille_across_tied_interface():
    # The wall shear: 2 walls x length 2 x mu |dU/dx| = 2 * 2 * 0.1 * 4 = 1.6 along +y, less
    # what the inflow's pressure puts on the walls' corner nodes (as in test_fluid).
    tied_poiseuille("quad")
    tied_poiseuille("tri")


TIED_POISEUILLE_3D = """\
dimension: 3
mesh: {geo: body.geo, order: 2}
materials: {oil: {model: newtonian_fluid, density: 1, viscosity: 0.1}}
bodies: [{region: lower, material: oil}, {region: upper, material: oil}]
boundary_conditions:
  - {region: bottom, type: velocity, value: [0, 0, "4*x*(1-x)"]}
  - {region: left, type: velocity, value: [0, 0, 0]}
  - {region: right, type: velocity, value: [0, 0, 0]}
  - {region: front, type: velocity, components: [y], value: [0]}
  - {region: back, type: velocity, components: [y], value: [0]}
interfaces:
  - {name: cut, type: mesh_tying, slave: upper_bottom, master: lower_top}
time: {integrator: static, end: 1, steps: 1}
output:
  exact_velocity: [0, 0, "4*x*(1-x)"]
  exact_pressure: "0.8*(2-z)"
"""


def test_poiseuille_across_tied_interface_3d():
    """Plane Poiseuille flow along z through two cubes stacked in z and meshed independently
    (no-slip at x = 0 and 1, slip walls at y = 0 and 1): exact on tet10 (whose tri6 slave
    facets use the modified dual basis) and hex27."""
    for kind, sizes in (("tet", (0.5, 0.4)), ("hex", (0.5, 0.34))):
        work = tempfile.mkdtemp(prefix="seam_fluid_tied_")
        H.write_case(work, "body.geo", geometry.tied_boxes(*sizes, order=2, kind=kind))
        out = H.solve(H.write_case(work, "case.yaml", TIED_POISEUILLE_3D))
        err = H.read_csv(os.path.join(out, "errors.csv"))[-1]
        H.cleanup(work, out)
        print("   %s: velocity L2 %.2e, pressure L2 %.2e"
              % (kind, err["velocity_l2_error"], err["pressure_l2_error"]))
        if err["velocity_l2_error"] > 1e-10 or err["pressure_l2_error"] > 1e-10:
            raise AssertionError("3D Poiseuille across the tied interface is not exact: %s" % err)


def test_uniform_flow_tied_stabilized():
    """Stabilized linear cells (tri3, quad4) tied: a uniform flow entering at the bottom with a
    tangential part, walls moving with it, leaves both meshes uniform (exact solution)."""
    text = TIED_POISEUILLE.replace("order: 2", "order: 1")
    for old, new in (('[0, "4*x*(1-x)"]', '[0.3, 1]'), ("[0, 0]", "[0.3, 1]"),
                     ('"0.8*(2-y)"', '"0"')):
        text = text.replace(old, new)
    for kind in ("tri", "quad"):
        work = tempfile.mkdtemp(prefix="seam_fluid_tied_")
        H.write_case(work, "body.geo", geometry.tied_rectangles(0.25, 0.2, order=1, kind=kind))
        out = H.solve(H.write_case(work, "case.yaml", text))
        err = H.read_csv(os.path.join(out, "errors.csv"))[-1]
        H.cleanup(work, out)
        print("   %s: velocity L2 %.2e, pressure L2 %.2e"
              % (kind, err["velocity_l2_error"], err["pressure_l2_error"]))
        if err["velocity_l2_error"] > 1e-12 or err["pressure_l2_error"] > 1e-12:
            raise AssertionError("the uniform flow is not kept across the interface: %s" % err)


def test_poiseuille_tied_three_ranks():
    one, three = tied_poiseuille("tri"), tied_poiseuille("tri", np=3)
    H.assert_close(three["fy"], one["fy"], rtol=1e-10, what="wall force on 3 ranks")


MOTION_2D = ('["0.1*sin(_pi*x)*sin(_pi*y/2)*sin(3*t) + 0.05*x*y*t*t",'
             ' "0.08*sin(_pi*x/2)*cos(_pi*y/4)*(1-cos(4*t)) - 0.04*y*t"]')


# The pseudo-elastic mesh moved by its boundary: the outflow and both sides of the interface.
PSEUDO_ELASTIC = (
    "  - {region: top, type: mesh_displacement, value: [\"0.1*sin(_pi*x)*sin(2*t)\", "
    "\"0.05*sin(_pi*x)*t\"]}\n"
    "  - {region: upper_bottom, type: mesh_displacement, value: [\"0.05*sin(_pi*x)*sin(2*t)\", "
    "\"0.04*sin(_pi*x)*t\"]}\n"
    "  - {region: lower_top, type: mesh_displacement, value: [\"0.05*sin(_pi*x)*sin(2*t)\", "
    "\"0.04*sin(_pi*x)*t\"]}\n")


def moving_tied(text, motion, kind, np=1):
    """The tied rectangles (quad9 or tri6) with both bodies moved by the prescribed `motion`
    (None: pseudo-elastic, PSEUDO_ELASTIC), in generalized-alpha (8 steps to t = 1) from an
    initial velocity equal to the first velocity condition's: the largest velocity and pressure
    L2 errors over the steps and the last wall force."""
    model = ("{model: prescribed, displacement: %s}" % motion if motion else
             "{model: pseudo_elastic}")
    text = text.replace("{region: lower, material: oil}, {region: upper, material: oil}",
                        "{region: lower, material: oil, mesh_motion: %s}, {region: upper, "
                        "material: oil, mesh_motion: %s}" % (model, model))
    if not motion:
        text = text.replace("interfaces:", PSEUDO_ELASTIC + "interfaces:")
    start = text.split("value: ")[1].split("}")[0]
    text = text.replace("time: {integrator: static, end: 1, steps: 1}",
                        "initial_conditions: [{region: lower, velocity: %s}, {region: upper, "
                        "velocity: %s}]\ntime: {integrator: generalized_alpha, rho_inf: 0.5, "
                        "end: 1, steps: 8}" % (start, start))
    work = tempfile.mkdtemp(prefix="seam_fluid_tied_")
    H.write_case(work, "body.geo", geometry.tied_rectangles(0.25, 0.2, order=2, kind=kind))
    out = H.solve(H.write_case(work, "case.yaml", text), np=np)
    errors = H.read_csv(os.path.join(out, "errors.csv"))
    force = H.read_csv(os.path.join(out, "forces.csv"))[-1]
    H.cleanup(work, out)
    worst_u = max(e["velocity_l2_error"] for e in errors)
    worst_p = max(e["pressure_l2_error"] for e in errors)
    print("   %s, np %d, %s, %d steps: largest velocity L2 error %.2e, pressure %.2e, wall force "
          "y %.12f" % (kind, np, "prescribed" if motion else "pseudo-elastic", len(errors), worst_u,
                       worst_p, force["fy"]))
    if len(errors) != 8:
        raise AssertionError("%d steps written, expected 8" % len(errors))
    return worst_u, worst_p, force


def test_free_stream_tied_moving_mesh():
    """A uniform flow through two non-matching tied meshes under a smooth mesh motion."""
    text = TIED_POISEUILLE.replace('[0, "4*x*(1-x)"]', "[0.3, 1]").replace("[0, 0]", "[0.3, 1]")
    text = text.replace('"0.8*(2-y)"', '"0"')
    for kind, np, motion in (("quad", 1, MOTION_2D), ("tri", 1, MOTION_2D), ("tri", 3, MOTION_2D),
                             ("quad", 1, None)):
        u, p, _ = moving_tied(text, motion, kind, np=np)
        if u > 1e-12 or p > 1e-11:
            raise AssertionError("%s, np %d, %s: the uniform flow is not kept through the moving "
                                 "tied meshes: velocity %.3e, pressure %.3e"
                                 % (kind, np, "prescribed" if motion else "pseudo-elastic", u, p))


def test_poiseuille_tied_translating_mesh():
    """Poiseuille flow across a tied interface on a rigidly translating mesh."""
    text = TIED_POISEUILLE.replace('[0, "4*x*(1-x)"]', '[0.3, "0.2 + 4*x*(1-x)"]')
    text = text.replace("[0, 0]", "[0.3, 0.2]").replace("  probes: [[0.3, 1.0], [0.7, 1.5]]\n", "")
    text = text.replace('exact_velocity: [0.3, "0.2 + 4*x*(1-x)"]',
                        'exact_velocity: [0.3, "0.2 + 4*(x-0.3*t)*(1-(x-0.3*t))"]')
    text = text.replace('"0.8*(2-y)"', '"0.8*(2-(y-0.2*t))"')
    for kind, np in (("quad", 1), ("tri", 1), ("tri", 3)):
        fixed = tied_poiseuille(kind)
        u, p, force = moving_tied(text, '["0.3*t", "0.2*t"]', kind, np=np)
        if u > 1e-10 or p > 1e-10:
            raise AssertionError("%s, np %d: Poiseuille flow across the tied interface of the "
                                 "translating mesh is not exact: velocity %.3e, pressure %.3e"
                                 % (kind, np, u, p))
        H.assert_close(force["fy"], fixed["fy"], rtol=1e-10,
                       what="wall force on the translating mesh (%s, np %d)" % (kind, np))


def split_dfg_geo(h, hc, xc=0.6, extra=3, conforming=False):
    """The DFG channel cut at x = xc into two surfaces meshed independently; the cut has
    `extra` more cells on its downstream side than upstream (non-matching). `conforming`: the
    two surfaces share the cut (one mesh, the upstream part's cells the same)."""
    n = max(2, round(0.41 / h))
    if conforming:
        downstream = ["Point(12) = {2.2, 0, 0, h}; Point(13) = {2.2, 0.41, 0, h};",
                      "Line(11) = {2, 12}; Line(12) = {12, 13}; Line(13) = {13, 3};",
                      "Curve Loop(3) = {11, 12, 13, -2}; Plane Surface(2) = {3};",
                      "Transfinite Curve{2} = %d;" % (n + 1)]
    else:
        downstream = [
            "Point(11) = {%g, 0, 0, h}; Point(12) = {2.2, 0, 0, h};" % xc,
            "Point(13) = {2.2, 0.41, 0, h}; Point(14) = {%g, 0.41, 0, h};" % xc,
            "Line(11) = {11, 12}; Line(12) = {12, 13}; Line(13) = {13, 14};",
            "Line(14) = {14, 11};",
            "Curve Loop(3) = {11, 12, 13, 14}; Plane Surface(2) = {3};",
            "Transfinite Curve{2} = %d; Transfinite Curve{14} = %d;" % (n + 1, n + 1 + extra),
            'Physical Curve("cut_left") = {2}; Physical Curve("cut_right") = {14};']
    return "\n".join([
        "h = %g; hc = %g;" % (h, hc),
        "Geometry.AutoCoherence = %d;" % (1 if conforming else 0),
        "Point(1) = {0, 0, 0, h}; Point(2) = {%g, 0, 0, h};" % xc,
        "Point(3) = {%g, 0.41, 0, h}; Point(4) = {0, 0.41, 0, h};" % xc,
        "Point(5) = {0.2, 0.2, 0, hc}; Point(6) = {0.25, 0.2, 0, hc};",
        "Point(7) = {0.2, 0.25, 0, hc}; Point(8) = {0.15, 0.2, 0, hc};",
        "Point(9) = {0.2, 0.15, 0, hc};",
        "Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};",
        "Circle(5) = {6, 5, 7}; Circle(6) = {7, 5, 8}; Circle(7) = {8, 5, 9};",
        "Circle(8) = {9, 5, 6};",
        "Curve Loop(1) = {1, 2, 3, 4}; Curve Loop(2) = {5, 6, 7, 8};",
        "Plane Surface(1) = {1, 2};",
    ] + downstream + [
        "Field[1] = Distance; Field[1].CurvesList = {5, 6, 7, 8};",
        "Field[1].NumPointsPerCurve = 200;",
        "Field[2] = Threshold; Field[2].InField = 1; Field[2].SizeMin = hc;",
        "Field[2].SizeMax = h; Field[2].DistMin = 0.0; Field[2].DistMax = 0.3;",
        "Background Field = 2;",
        "Mesh.MeshSizeExtendFromBoundary = 0; Mesh.MeshSizeFromPoints = 0;",
        "Mesh.MeshSizeFromCurvature = 0;",
        'Physical Curve("inflow") = {4}; Physical Curve("outflow") = {12};',
        'Physical Curve("walls") = {1, 3, 11, 13};',
        'Physical Curve("cylinder") = {5, 6, 7, 8};',
        'Physical Surface("upstream") = {1}; Physical Surface("downstream") = {2};',
    ]) + "\n"


def dfg_split(h, hc, np=1, conforming=False, solver=None, options=(), summary=None):
    work = tempfile.mkdtemp(prefix="seam_dfg_tied_")
    H.write_case(work, "dfg.geo", split_dfg_geo(h, hc, conforming=conforming))
    with open(os.path.join(F.EXAMPLE, "dfg_2d1.yaml")) as f:
        text = f.read()
    tie = ("" if conforming else "interfaces:\n"
           "  - {name: cut, type: mesh_tying, slave: cut_right, master: cut_left}\n")
    text = text.replace("  - {region: fluid, material: air}\n",
                        "  - {region: upstream, material: air}\n"
                        "  - {region: downstream, material: air}\n" + tie)
    text += "solver: %s\n" % solver if solver else ""
    out = H.solve(H.write_case(work, "case.yaml", text), np=np,
                  extra=["--"] + list(options) if options else ())
    f = H.read_csv(os.path.join(out, "forces.csv"))[-1]
    probes = H.last_step_rows(H.read_csv(os.path.join(out, "probes.csv")))
    info = H.read_json(os.path.join(out, "summary.json"))
    dofs = info["dofs"]
    if summary is not None:
        summary.update(info)
    H.cleanup(work, out)
    scale = 2 / (1.0 * 0.2 ** 2 * 0.1)
    cd, cl = scale * f["fx"], scale * f["fy"]
    dp = probes[0]["pressure"] - probes[1]["pressure"]
    print("   %s mesh, h = %g, hc = %g, np = %d, %d dofs: c_D = %.6f, c_L = %.6f, dp = %.6f"
          % ("one" if conforming else "tied", h, hc, np, dofs, cd, cl, dp))
    return cd, cl, dp


def compare_split(h, hc):
    single = dfg_split(h, hc, conforming=True)
    cut = dfg_split(h, hc)
    print("   cut against uncut: c_D %+.4f %%, c_L %+.4f %%, dp %+.4f %%"
          % tuple(100 * (cut[k] / single[k] - 1) for k in range(3)))
    H.assert_close(cut[0], single[0], rtol=1e-3, what="c_D of the cut mesh")
    H.assert_close(cut[1], single[1], rtol=1e-3, what="c_L of the cut mesh")
    H.assert_close(cut[2], single[2], rtol=1e-3, what="pressure difference of the cut mesh")
    return cut


def test_dfg_2d1_cut():
    cut = compare_split(0.04, 0.006)
    three = dfg_split(0.04, 0.006, np=3)
    for k, what in enumerate(("c_D", "c_L", "pressure difference")):
        H.assert_close(three[k], cut[k], rtol=1e-8, what=what + " of the cut mesh on 3 ranks")


def pcd_used(info, what):
    """FGMRES iterations per Newton step of a PCD run; fails unless summary.json names PCD."""
    if not info["linear_solver"].endswith(", PCD)"):
        raise AssertionError("%s: solver %r, expected PCD" % (what, info["linear_solver"]))
    return info["linear_iterations"] / info["linear_solves"]


def test_pcd_tied():
    """PCD (`-fluid_schur pcd`) with tied fluid subdomains (docs/fluid.md, "PCD with tied
    subdomains"): the Poiseuille flow across the tied interface stays exact (quad9, tri6; tri6
    on 3 ranks), and DFG 2D-1 cut into two non-matching meshes gives MUMPS's c_D and dp to
    1e-8 and c_L to 1e-8 of c_D (the Newton tolerance bounds the residual relative to the force
    level, as in test_fluid.test_dfg_2d1_pcd), on 1 and 3 ranks."""
    for kind, np in (("quad", 1), ("tri", 1), ("tri", 3)):
        info = {}
        tied_poiseuille(kind, np=np, solver="{linear: iterative}", options=F.PCD, summary=info)
        print("   %d Newton steps, %.1f FGMRES iterations per step"
              % (info["linear_solves"], pcd_used(info, "Poiseuille")))
    direct = dfg_split(0.08, 0.012)
    for np in (1, 3):
        info = {}
        it = dfg_split(0.08, 0.012, np=np, solver="{linear: iterative}", options=F.PCD,
                       summary=info)
        print("   np = %d: %d Newton steps, %.1f FGMRES iterations per step"
              % (np, info["linear_solves"], pcd_used(info, "DFG 2D-1 cut")))
        for k, what in enumerate(("c_D", "c_L", "dp")):
            H.assert_close(it[k], direct[k], rtol=1e-8, atol=1e-8 * abs(direct[0]) if k == 1 else 0,
                           what="%s of the cut mesh, PCD against MUMPS on %d ranks" % (what, np))


def test_bad_input():
    tie = "interfaces: [{name: t, type: %s, slave: top, master: bottom%s}]\n"
    F.expect_bad("contact between fluids", ["contact", "fluid contact is not available"],
                 extra=tie % ("contact", ""))
    F.expect_bad("standard multipliers for fluids", ["dual multipliers, condensed"],
                 extra=tie % ("mesh_tying", ", multiplier: standard"))


if __name__ == "__main__":
    H.main([test_poiseuille_across_tied_interface, test_poiseuille_across_tied_interface_3d,
            test_uniform_flow_tied_stabilized, test_poiseuille_tied_three_ranks,
            test_free_stream_tied_moving_mesh, test_poiseuille_tied_translating_mesh,
            test_dfg_2d1_cut, test_pcd_tied, test_bad_input])
