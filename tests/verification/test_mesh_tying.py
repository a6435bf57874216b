"""Mortar mesh tying patch tests (issue: mortar mesh tying).

Two bodies of one material with non-matching meshes, tied by dual mortar multipliers
(condensed), under a load that makes the stress uniform. The exact solution is a linear
displacement field, which must come out exactly (1e-10) at probes on both sides of the
interface; the reaction equals the applied load; the multiplier's normal part equals the
normal stress. Flat and curved interfaces, 2D and 3D, linear and quadratic, either body as
slave, np = 1 and 3, and a Neo-Hookean finite-strain case (uniaxial stretch with nu = 0,
P = mu (lambda - 1/lambda)).
"""
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import geometry  # noqa: E402
import harness as H  # noqa: E402

E, NU, T = 100.0, 0.3, 2.0


def run_case(geo_text, yaml_text, np=1):
    work = tempfile.mkdtemp(prefix="seam_tie_")
    H.write_case(work, "body.geo", geo_text)
    yaml = H.write_case(work, "case.yaml", yaml_text)
    out = H.solve(yaml, np=np)
    return work, out


def linear_field_error(out, strains, origin):
    """Largest deviation of the probe displacements from the linear field."""
    worst = 0.0
    for p in H.last_step_rows(H.read_csv(os.path.join(out, "probes.csv"))):
        for i, comp in enumerate(("ux", "uy", "uz")):
            worst = max(worst, abs(p[comp] - strains[i] * (p["xyz"[i]] - origin[i])))
    return worst


def check_linear_field(out, strains, origin, scale, what):
    for p in H.last_step_rows(H.read_csv(os.path.join(out, "probes.csv"))):
        for i, comp in enumerate(("ux", "uy", "uz")):
            coord = p["xyz"[i]] - origin[i]
            H.assert_close(p[comp], strains[i] * coord, atol=1e-10 * scale,
                           what="%s probe %d %s" % (what, int(p["probe"]), comp))


def interface_line(slave, master, multiplier, strategy):
    return "  - {name: tie, type: mesh_tying, slave: %s, master: %s, multiplier: %s, strategy: %s}" % (
        slave, master, multiplier, strategy)


def tied_3d(kind, h, order, slave, master, direction, np=1, multiplier="dual",
            strategy="condensed", serendipity=False):
    """Uniaxial stress T along `direction` (z: normal to the interface, x: tangential)."""
    load_face = {"z": "top", "x": "right"}[direction]
    traction = {"z": "[0, 0, %g]" % T, "x": "[%g, 0, 0]" % T}[direction]
    yaml = "\n".join([
        "dimension: 3",
        "mesh: {geo: body.geo}",
        "materials: {m: {model: linear_elastic, young: %g, poisson: %g}}" % (E, NU),
        "bodies: [{region: lower, material: m}, {region: upper, material: m}]",
        "boundary_conditions:",
        "  - {region: bottom, type: dirichlet, components: [z], value: [0]}",
        "  - {region: left, type: dirichlet, components: [x], value: [0]}",
        "  - {region: front, type: dirichlet, components: [y], value: [0]}",
        "  - {region: %s, type: traction, value: %s}" % (load_face, traction),
        "interfaces:",
        interface_line(slave, master, multiplier, strategy),
        "time: {integrator: static, end: 1, steps: 1}",
        "output: {probes: [[0.3, 0.4, 0.5], [0.7, 0.2, 1.5], [0.5, 0.5, 1.0], [0.9, 0.9, 1.9]]}",
    ]) + "\n"
    work, out = run_case(geometry.tied_boxes(h[0], h[1], order, kind, serendipity), yaml, np)
    main, lateral = T / E, -NU * T / E
    strains = (main, lateral, lateral) if direction == "x" else (lateral, lateral, main)
    check_linear_field(out, strains, (0, 0, 0), 2 * main, "%s %s" % (kind, direction))
    reactions = H.last_step_rows(H.read_csv(os.path.join(out, "reactions.csv")))
    if direction == "z":
        bottom = [r for r in reactions if r["region"] == "bottom"][0]
        H.assert_close(bottom["fz"], -T, rtol=1e-10, what="reaction")
        # The multiplier is minus the slave traction: its normal part is the normal stress
        # with the sign of the slave's outward normal.
        nodes = H.read_csv(os.path.join(out, "interface_tie.csv"))
        for n in nodes:
            if n["status"] == "tied":
                H.assert_close(n["normal_traction"], -T, rtol=1e-8, what="multiplier")
    H.cleanup(work, out)


def tied_2d(geo, order, slave, master, plane="strain", np=1, curved=False, multiplier="dual",
            strategy="condensed"):
    if curved:
        bcs = ["  - {region: left, type: dirichlet, components: [x], value: [0]}",
               "  - {region: bottom, type: dirichlet, components: [y], value: [0]}",
               "  - {region: right, type: traction, value: [%g, 0]}" % T]
        bodies = "[{region: plate, material: m}, {region: disk, material: m}]"
        probes = [[0.1, 0.2], [0.45, 0.1], [-0.8, 0.7], [0.0, 0.5]]
        origin = (-1, -1, 0)
    else:
        bcs = ["  - {region: bottom, type: dirichlet, components: [y], value: [0]}",
               "  - {region: left, type: dirichlet, components: [x], value: [0]}",
               "  - {region: top, type: traction, value: [0, %g]}" % T]
        bodies = "[{region: lower, material: m}, {region: upper, material: m}]"
        probes = [[0.3, 0.4], [0.7, 1.5], [0.5, 1.0], [0.9, 1.9]]
        origin = (0, 0, 0)
    yaml = "\n".join([
        "dimension: 2",
        "plane: %s" % plane,
        "mesh: {geo: body.geo}",
        "materials: {m: {model: linear_elastic, young: %g, poisson: %g}}" % (E, NU),
        "bodies: %s" % bodies,
        "boundary_conditions:"] + bcs + [
        "interfaces:",
        interface_line(slave, master, multiplier, strategy),
        "time: {integrator: static, end: 1, steps: 1}",
        "output: {probes: %s}" % probes,
    ]) + "\n"
    work, out = run_case(geo, yaml, np)
    main = (1 - NU ** 2) * T / E
    lateral = -NU * (1 + NU) * T / E
    strains = (main, lateral, 0) if curved else (lateral, main, 0)
    summary = H.read_json(os.path.join(out, "summary.json"))
    itf = summary["interfaces"][0]
    if itf["integration_cells"] <= 0:
        raise AssertionError("no integration cells reported")
    if curved:
        # Two discretizations of one circle never coincide, so the uniform state is exact only
        # up to the geometric mismatch of the polygons: the test checks that the error is small
        # and vanishes under refinement instead.
        error = linear_field_error(out, strains, origin) / (2 * main)
        H.cleanup(work, out)
        return error
    check_linear_field(out, strains, origin, 2 * main, "2D")
    H.cleanup(work, out)


def test_3d_tet_normal(): tied_3d("tet", (0.34, 0.26), 1, "upper_bottom", "lower_top", "z")
def test_3d_tet_normal_np3(): tied_3d("tet", (0.34, 0.26), 1, "upper_bottom", "lower_top", "z", np=3)
def test_3d_tet_tangential_swapped(): tied_3d("tet", (0.26, 0.34), 1, "lower_top", "upper_bottom", "x")
def test_3d_hex_normal(): tied_3d("hex", (0.34, 0.26), 1, "upper_bottom", "lower_top", "z")
def test_3d_hex27_tangential_np3(): tied_3d("hex", (0.5, 0.34), 2, "lower_top", "upper_bottom", "x", np=3)
def test_3d_tet_saddle_dual_np3(): tied_3d("tet", (0.34, 0.26), 1, "upper_bottom", "lower_top", "z", np=3, strategy="saddle_point")
def test_3d_tet_saddle_standard(): tied_3d("tet", (0.34, 0.26), 1, "lower_top", "upper_bottom", "x", multiplier="standard", strategy="saddle_point")
def test_3d_tet10_saddle_standard(): tied_3d("tet", (0.5, 0.4), 2, "upper_bottom", "lower_top", "z", multiplier="standard", strategy="saddle_point")
def test_3d_hex27_saddle_standard_np3(): tied_3d("hex", (0.5, 0.34), 2, "upper_bottom", "lower_top", "z", np=3, multiplier="standard", strategy="saddle_point")
def test_2d_tri6_saddle_standard(): tied_2d(geometry.tied_rectangles(0.3, 0.2, 2), 2, "upper_bottom", "lower_top", multiplier="standard", strategy="saddle_point")
def test_2d_quad_saddle_dual_np3(): tied_2d(geometry.tied_rectangles(0.2, 0.3, 1, "quad"), 1, "lower_top", "upper_bottom", np=3, strategy="saddle_point")


def test_3d_tet10_dual_condensed(): tied_3d("tet", (0.5, 0.4), 2, "upper_bottom", "lower_top", "z")
def test_3d_tet10_dual_condensed_tangential_np3(): tied_3d("tet", (0.5, 0.4), 2, "lower_top", "upper_bottom", "x", np=3)
def test_3d_hex_nonparallelogram_faces():
    """Hexahedra from split tetrahedra: quad4 interface faces that are not parallelograms,
    where no cell rule integrates the mortar integrands exactly (Puso & Laursen 2004). seam
    takes the degree-8 cell rule for such interfaces: reaction to 1e-7, multiplier to 1e-5
    (the degree-5 rule gave 7.5e-7 and 2.4e-4)."""
    yaml = "\n".join([
        "dimension: 3",
        "mesh: {geo: body.geo}",
        "materials: {m: {model: linear_elastic, young: %g, poisson: 0}}" % E,
        "bodies: [{region: lower, material: m}, {region: upper, material: m}]",
        "boundary_conditions:",
        "  - {region: bottom, type: dirichlet, components: [z], value: [0]}",
        "  - {region: left, type: dirichlet, components: [x], value: [0]}",
        "  - {region: front, type: dirichlet, components: [y], value: [0]}",
        "  - {region: top, type: traction, value: [0, 0, %g]}" % T,
        "interfaces:",
        interface_line("upper_bottom", "lower_top", "dual", "condensed"),
        "time: {integrator: static, end: 1, steps: 1}",
    ]) + "\n"
    work, out = run_case(geometry.tied_boxes(0.5, 0.35, 1, "hex_split"), yaml, 1)
    bottom = [r for r in H.last_step_rows(H.read_csv(os.path.join(out, "reactions.csv")))
              if r["region"] == "bottom"][0]
    H.assert_close(bottom["fz"], -T, rtol=1e-7, what="reaction")
    worst = max(abs(n["normal_traction"] + T) / T
                for n in H.read_csv(os.path.join(out, "interface_tie.csv")) if n["status"] == "tied")
    print("   non-parallelogram quad4 faces: multiplier error %.2e, reaction error %.2e"
          % (worst, abs(bottom["fz"] + T) / T))
    if worst > 1e-5:
        raise AssertionError("multiplier error %.3e > 1e-5" % worst)
    H.cleanup(work, out)


def test_3d_hex20_dual_condensed(): tied_3d("hex", (0.5, 0.34), 2, "upper_bottom", "lower_top", "z", serendipity=True)


def test_2d_tri_flat(): tied_2d(geometry.tied_rectangles(0.3, 0.2), 1, "upper_bottom", "lower_top")
def test_2d_quad_flat_np3(): tied_2d(geometry.tied_rectangles(0.2, 0.3, 1, "quad"), 1, "lower_top", "upper_bottom", np=3)
def test_2d_tri6_flat(): tied_2d(geometry.tied_rectangles(0.3, 0.2, 2), 2, "upper_bottom", "lower_top", plane="strain")
# Tied interfaces that reach a clamped boundary. The slave nodes on the clamped face carry no
# multiplier; the boundary modification of the dual basis (Wohlmuth 2001; Popp et al. 2013)
# hands their share to the neighbouring slave nodes, so the multipliers still reproduce a
# constant traction there. Loads: u = x (a, b, c) with the left face x = 0 clamped, a uniform
# stress with a normal and a tangential traction on the interface z = 1 (y = 1 in 2D).
LAME = E * NU / ((1 + NU) * (1 - 2 * NU))
MU = E / (2 * (1 + NU))
GRAD = (0.01, 0.004, 0.006)


def clamped_3d(kind, h, order, slave, master, np=1, multiplier="dual", strategy="condensed",
               serendipity=False):
    a, b, c = GRAD
    sxx, syy, sxy, sxz = (LAME + 2 * MU) * a, LAME * a, MU * b, MU * c
    vec = lambda v: "[%.17g, %.17g, %.17g]" % tuple(v)  # noqa: E731
    yaml = "\n".join([
        "dimension: 3",
        "mesh: {geo: body.geo}",
        "materials: {m: {model: linear_elastic, young: %g, poisson: %g}}" % (E, NU),
        "bodies: [{region: lower, material: m}, {region: upper, material: m}]",
        "boundary_conditions:",
        "  - {region: left, type: dirichlet, components: [x, y, z], value: [0, 0, 0]}",
        "  - {region: right, type: traction, value: %s}" % vec((sxx, sxy, sxz)),
        "  - {region: front, type: traction, value: %s}" % vec((-sxy, -syy, 0)),
        "  - {region: back, type: traction, value: %s}" % vec((sxy, syy, 0)),
        "  - {region: bottom, type: traction, value: %s}" % vec((-sxz, 0, -syy)),
        "  - {region: top, type: traction, value: %s}" % vec((sxz, 0, syy)),
        "interfaces:",
        interface_line(slave, master, multiplier, strategy),
        "time: {integrator: static, end: 1, steps: 1}",
        "output: {probes: [[0.3, 0.4, 0.5], [0.7, 0.2, 1.5], [0.05, 0.5, 0.97], "
        "[0.05, 0.3, 1.03], [0.02, 0.9, 1.0], [0.9, 0.9, 1.9]]}",
    ]) + "\n"
    work, out = run_case(geometry.tied_boxes(h[0], h[1], order, kind, serendipity), yaml, np)
    what = "clamped %s order %d %s %s np=%d" % (kind, order, multiplier, strategy, np)
    try:
        check_shear_field(out, GRAD, a, what)
        check_interface_traction(out, -syy, what)
    finally:
        H.cleanup(work, out)


def clamped_2d(kind, h, order, slave, master, np=1, multiplier="dual", strategy="condensed"):
    a, c = GRAD[0], GRAD[2]
    sxx, syy, sxy = (LAME + 2 * MU) * a, LAME * a, MU * c
    yaml = "\n".join([
        "dimension: 2",
        "mesh: {geo: body.geo}",
        "materials: {m: {model: linear_elastic, young: %g, poisson: %g}}" % (E, NU),
        "bodies: [{region: lower, material: m}, {region: upper, material: m}]",
        "boundary_conditions:",
        "  - {region: left, type: dirichlet, components: [x, y], value: [0, 0]}",
        "  - {region: right, type: traction, value: [%.17g, %.17g]}" % (sxx, sxy),
        "  - {region: bottom, type: traction, value: [%.17g, %.17g]}" % (-sxy, -syy),
        "  - {region: top, type: traction, value: [%.17g, %.17g]}" % (sxy, syy),
        "interfaces:",
        interface_line(slave, master, multiplier, strategy),
        "time: {integrator: static, end: 1, steps: 1}",
        "output: {probes: [[0.3, 0.4], [0.7, 1.5], [0.04, 0.97], [0.04, 1.03], [0.01, 1.0]]}",
    ]) + "\n"
    work, out = run_case(geometry.tied_rectangles(h[0], h[1], order, kind), yaml, np)
    what = "clamped 2D %s order %d %s %s np=%d" % (kind, order, multiplier, strategy, np)
    try:
        check_shear_field(out, (a, c, 0), a, what)
        check_interface_traction(out, -syy, what)
    finally:
        H.cleanup(work, out)


def check_shear_field(out, grad, scale, what):
    """Probe displacements against u = x * grad."""
    for p in H.last_step_rows(H.read_csv(os.path.join(out, "probes.csv"))):
        for i, comp in enumerate(("ux", "uy", "uz")):
            H.assert_close(p[comp], grad[i] * p["x"], atol=1e-10 * scale,
                           what="%s probe %d %s" % (what, int(p["probe"]), comp))


def check_interface_traction(out, expected, what):
    """The multiplier's normal part is minus the normal stress at every tied slave node."""
    nodes = H.read_csv(os.path.join(out, "interface_tie.csv"))
    tied = [n for n in nodes if n["status"] == "tied"]
    if not tied:
        raise AssertionError("%s: no tied slave node" % what)
    for n in tied:
        H.assert_close(n["normal_traction"], expected, rtol=1e-8,
                       what="%s multiplier at node %d" % (what, int(n["node"])))


def test_clamped_3d_tet(): clamped_3d("tet", (0.34, 0.26), 1, "upper_bottom", "lower_top")
def test_clamped_3d_tet_np3(): clamped_3d("tet", (0.26, 0.34), 1, "upper_bottom", "lower_top", np=3)
def test_clamped_3d_hex(): clamped_3d("hex", (0.34, 0.26), 1, "lower_top", "upper_bottom")
def test_clamped_3d_hex_np3(): clamped_3d("hex", (0.26, 0.34), 1, "upper_bottom", "lower_top", np=3)
def test_clamped_3d_tet10(): clamped_3d("tet", (0.5, 0.4), 2, "upper_bottom", "lower_top")
def test_clamped_3d_hex20_np3(): clamped_3d("hex", (0.5, 0.34), 2, "upper_bottom", "lower_top", np=3, serendipity=True)
def test_clamped_3d_saddle_dual_np3(): clamped_3d("tet", (0.34, 0.26), 1, "upper_bottom", "lower_top", np=3, strategy="saddle_point")
def test_clamped_3d_saddle_standard(): clamped_3d("hex", (0.34, 0.26), 1, "lower_top", "upper_bottom", multiplier="standard", strategy="saddle_point")
def test_clamped_2d_tri(): clamped_2d("tri", (0.3, 0.2), 1, "lower_top", "upper_bottom")
def test_clamped_2d_quad_np3(): clamped_2d("quad", (0.2, 0.3), 1, "upper_bottom", "lower_top", np=3)
def test_clamped_2d_tri6(): clamped_2d("tri", (0.3, 0.2), 2, "lower_top", "upper_bottom")
def test_clamped_2d_saddle_standard_np3(): clamped_2d("tri", (0.3, 0.2), 1, "lower_top", "upper_bottom", np=3, multiplier="standard", strategy="saddle_point")


# Dual multipliers on tri6/quad8 slave faces (modified basis, d_S = T d~_S) as a saddle
# point, B = [D T^{-1}, -M], against the condensed strategy under a non-uniform load (a
# bending traction, no closed form): the two must give the same displacements and multipliers
# to solver tolerance.
def strategies_agree(kind, h, serendipity, np=1):
    def run(strategy):
        yaml = "\n".join([
            "dimension: 3",
            "mesh: {geo: body.geo}",
            "materials: {m: {model: linear_elastic, young: %g, poisson: %g}}" % (E, NU),
            "bodies: [{region: lower, material: m}, {region: upper, material: m}]",
            "boundary_conditions:",
            "  - {region: left, type: dirichlet, components: [x, y, z], value: [0, 0, 0]}",
            "  - {region: top, type: traction, value: [0.3, 0, '-0.5*x*y']}",
            "  - {region: right, type: traction, value: [0, '0.2*z', 0]}",
            "interfaces:",
            interface_line("upper_bottom", "lower_top", "dual", strategy),
            "time: {integrator: static, end: 1, steps: 1}",
            "solver: {newton: {tolerance: 1.0e-12}}",
            "output: {probes: [[0.3, 0.4, 0.5], [0.7, 0.2, 1.5], [0.5, 0.5, 1.0], [0.95, 0.9, 1.9]]}",
        ]) + "\n"
        work, out = run_case(geometry.tied_boxes(h[0], h[1], 2, kind, serendipity), yaml, np)
        probes = H.last_step_rows(H.read_csv(os.path.join(out, "probes.csv")))
        nodes = H.read_csv(os.path.join(out, "interface_tie.csv"))
        H.cleanup(work, out)
        return probes, nodes
    (pc, nc), (ps, ns) = run("condensed"), run("saddle_point")
    scale = max(abs(p[c]) for p in pc for c in ("ux", "uy", "uz"))
    what = "%s order 2 dual saddle vs condensed" % ("hex20" if serendipity else kind)
    for a, b in zip(pc, ps):
        for c in ("ux", "uy", "uz"):
            H.assert_close(b[c], a[c], atol=1e-9 * scale, what="%s probe %d %s" % (what, int(a["probe"]), c))
    lscale = max(abs(n["normal_traction"]) for n in nc)
    for a, b in zip(nc, ns):
        for c in ("ux", "uy", "uz"):
            H.assert_close(b[c], a[c], atol=1e-9 * scale, what="%s node %d %s" % (what, int(a["node"]), c))
        H.assert_close(b["normal_traction"], a["normal_traction"], atol=1e-7 * lscale,
                       what="%s node %d multiplier" % (what, int(a["node"])))


def test_3d_tet10_saddle_dual(): strategies_agree("tet", (0.5, 0.4), False)
def test_3d_hex20_saddle_dual_np3(): strategies_agree("hex", (0.5, 0.34), True, np=3)
def test_3d_tet10_saddle_dual_patch(): tied_3d("tet", (0.5, 0.4), 2, "upper_bottom", "lower_top", "z", strategy="saddle_point")
def test_3d_hex20_saddle_dual_patch_np3(): tied_3d("hex", (0.5, 0.34), 2, "lower_top", "upper_bottom", "x", np=3, strategy="saddle_point", serendipity=True)


def curved_study(order, slave, master, expected_rate, np=1):
    errors = []
    for h in (0.2, 0.1, 0.05):
        errors.append(tied_2d(geometry.plate_with_inclusion(h, 0.6 * h, order), order, slave,
                              master, curved=True, np=np))
    print("curved interface, order %d: relative errors %s" % (order, errors))
    if errors[0] > 1e-3:
        raise AssertionError("curved patch error too large: %s" % errors)
    for a, b in zip(errors, errors[1:]):
        if b > a / expected_rate:
            raise AssertionError("curved patch error does not vanish under refinement: %s" % errors)


def test_2d_curved_linear(): curved_study(1, "rim", "hole", 2.5)
def test_2d_curved_quadratic(): curved_study(2, "hole", "rim", 2.5)
def test_2d_curved_np3(): curved_study(1, "rim", "hole", 2.5, np=3)


def test_neo_hooke_stretch():
    """Finite strain across the tied interface: stretch 1.5 along z with nu = 0."""
    stretch = 1.5
    yaml = "\n".join([
        "dimension: 3",
        "mesh: {geo: body.geo}",
        "materials: {m: {model: neo_hooke, young: 10, poisson: 0.0}}",
        "bodies: [{region: lower, material: m}, {region: upper, material: m}]",
        "boundary_conditions:",
        "  - {region: bottom, type: dirichlet, components: [z], value: [0]}",
        "  - {region: left, type: dirichlet, components: [x], value: [0]}",
        "  - {region: front, type: dirichlet, components: [y], value: [0]}",
        "  - {region: top, type: dirichlet, components: [z], value: ['%.17g*t']}" % (2 * (stretch - 1)),
        "interfaces:",
        "  - {name: tie, type: mesh_tying, slave: upper_bottom, master: lower_top}",
        "time: {integrator: static, end: 1, steps: 4}",
        "solver: {newton: {tolerance: 1.0e-12}}",
        "output: {probes: [[0.3, 0.4, 0.5], [0.7, 0.2, 1.5]]}",
    ]) + "\n"
    work, out = run_case(geometry.tied_boxes(0.5, 0.34, 1, "tet"), yaml)
    mu = 10 / 2.0
    reactions = H.last_step_rows(H.read_csv(os.path.join(out, "reactions.csv")))
    bottom = [r for r in reactions if r["region"] == "bottom"][0]
    H.assert_close(bottom["fz"], -mu * (stretch - 1 / stretch), rtol=1e-9, what="P33 reaction")
    check_linear_field(out, (0, 0, stretch - 1), (0, 0, 0), 1.0, "neo-hooke")
    H.cleanup(work, out)


if __name__ == "__main__":
    H.main([test_3d_tet_saddle_dual_np3, test_3d_tet_saddle_standard, test_3d_tet10_saddle_standard,
            test_3d_hex27_saddle_standard_np3, test_2d_tri6_saddle_standard,
            test_2d_quad_saddle_dual_np3, test_3d_tet10_dual_condensed,
            test_3d_tet10_dual_condensed_tangential_np3, test_3d_hex20_dual_condensed,
            test_3d_hex_nonparallelogram_faces,
            test_3d_tet_normal, test_3d_tet_normal_np3, test_3d_tet_tangential_swapped,
            test_3d_hex_normal, test_3d_hex27_tangential_np3, test_2d_tri_flat,
            test_2d_quad_flat_np3, test_2d_tri6_flat, test_2d_curved_linear,
            test_2d_curved_quadratic, test_2d_curved_np3, test_neo_hooke_stretch,
            test_clamped_3d_tet, test_clamped_3d_tet_np3, test_clamped_3d_hex,
            test_clamped_3d_hex_np3, test_clamped_3d_tet10, test_clamped_3d_hex20_np3,
            test_clamped_3d_saddle_dual_np3, test_clamped_3d_saddle_standard,
            test_clamped_2d_tri, test_clamped_2d_quad_np3, test_clamped_2d_tri6,
            test_clamped_2d_saddle_standard_np3, test_3d_tet10_saddle_dual,
            test_3d_hex20_saddle_dual_np3, test_3d_tet10_saddle_dual_patch,
            test_3d_hex20_saddle_dual_patch_np3])
