"""Energy-momentum contact on quadratic 3D faces (issue 13; docs/contact_dynamics.md §5).

Between two bodies (and as one `surface:` interface) the weighted gaps of a pair of quadratic
facets have exact second derivatives through the kernel of contact/gap_blocks_3d.cpp on
Hyper<81>, so the contact force is their discrete gradient: two blocks of one hex27 (quad9
faces) or hex20 (quad8) cell each, thrown at each other obliquely and spinning, keep the linear
and angular momentum to 1e-12 and no step gains more than 1e-10 of the energy (Newton
tolerance 1e-12); np = 3 equals np = 1.

Against a rigid obstacle the weighted gaps of a quadratic slave facet (tri6, quad8, quad9),
g~_j = int Phi_j g da with the dual basis of the modified shape functions on tri6/quad8
(Phi_j = A_jk N~_k) or N_j (standard, quad9), have exact second derivatives in the facet's
nodal positions (contact/rigid_obstacle_facet.cpp), so the contact force of the step is their
discrete gradient: the energy never rises by more than the Newton tolerance's scale and in
persistent contact it stays constant to it; against a plane the momentum along it and against
a sphere the angular momentum about its centre stay those of the start to 1e-12; np = 3
equals np = 1. Cases: the ring of test_rings.py extruded (hex27: quad9 faces; hex20: quad8)
and a ball of tet10 (tri6 faces).

With the force of the end of the step (the build before, measured with SEAM set to it) the
same cases gained up to 4.7e-5 (quad9 on the sphere), 1.1e-3 (quad9 on the plane, standard),
4.9e-4 (quad8), 1.1e-4 (tri6 on the sphere) of the energy in a step, the hex27 blocks 1.1e-3
(angular momentum 4.6e-3), the hex20 blocks 9.9e-2 (7.7e-3); docs/contact_dynamics.md §5.
"""
import math
import os
import re
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness as H  # noqa: E402
import test_contact as T  # noqa: E402
import test_rings as R  # noqa: E402

# A ball of radius 0.5 around (0, 0.55, 0.25), tetrahedra of second order (tri6 faces).
BALL_GEO = """SetFactory("OpenCASCADE");
Sphere(1) = {0, 0.55, 0.25, 0.5};
Mesh.CharacteristicLengthMax = 0.3;
Mesh.ElementOrder = 2;
Physical Volume("r0") = {1};
Physical Surface("r0_boundary") = {1};
"""


def obstacle_case(body, obstacle, multiplier="dual", steps=30, end=0.2):
    """The geometry and input of the ring ("quad9": hex27, "quad8": hex20) or the ball
    ("tri6") thrown obliquely and spinning onto a rigid plane or sphere under it
    (test_rings.ring_on_obstacle)."""
    if body == "tri6":
        geo = BALL_GEO
        velocity = '"0.4 - 0.5*(y - 0.55)", "-1 + 0.5*x", "0.1"'
    else:
        geo = R.ring_geo_3d(((0.0, 1.05),), 3, 1) + "Mesh.ElementOrder = 2;\n"
        if body == "quad8":
            geo += "Mesh.SecondOrderIncomplete = 1;\n"
        velocity = R.OBSTACLE_VELOCITY[3]
    yaml = (R.OBSTACLE_YAML.replace("DIM", "3").replace("VELOCITY", velocity)
            .replace("MULTIPLIER", "multiplier: %s," % multiplier)
            .replace("OBSTACLE", R.OBSTACLES[obstacle][3]).replace("STEPS", str(steps))
            .replace("END", str(end)))
    return geo, yaml


def on_obstacle(body, obstacle, multiplier="dual", np=1):
    """obstacle_case run; the energy figures of check_obstacle_energy."""
    geo, yaml = obstacle_case(body, obstacle, multiplier)
    rows, itf, newton = R.run_geo(geo, yaml, np)
    r = R.obstacle_energy(rows, itf, newton, "%s faces on a rigid %s, %s multipliers, np %d"
                          % (body, obstacle, multiplier, np))
    r["body"] = body
    return r


def check(r, obstacle):
    """test_rings.check_ring_on_obstacle (the ring's m |v| as the scale of the ball's
    momenta too, half of its own)."""
    R.check_ring_on_obstacle(r, 3, obstacle)


def test_quad9_on_obstacles():
    """quad9 faces (hex27 ring) on a rigid sphere (dual multipliers, np 1 and 3) and a plane
    (standard multipliers)."""
    r1 = on_obstacle("quad9", "sphere")
    check(r1, "sphere")
    r3 = on_obstacle("quad9", "sphere", np=3)
    check(r3, "sphere")
    R.check_np3_equals_np1(r3, r1)
    check(on_obstacle("quad9", "plane", multiplier="standard"), "plane")


def test_quad8_tri6_on_obstacles():
    """quad8 faces (hex20 ring) and tri6 faces (tet10 ball) on a rigid sphere and plane (dual
    multipliers of the modified basis)."""
    check(on_obstacle("quad8", "sphere"), "sphere")
    check(on_obstacle("tri6", "sphere"), "sphere")
    check(on_obstacle("tri6", "plane"), "plane")


# Two unit cubes of one cell each, b's face x = 1.002 facing a's x = 1, offset by (0.2, 0.1)
# in y and z; they close at 0.4 and spin, so the contact is eccentric; it holds from the
# second step on. A third cube c at rest far away lets np 3 partition the mesh.
BLOCKS_GEO = """SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Box(2) = {1.002, 0.2, 0.1, 1, 1, 1};
Box(3) = {-3, 0, 0, 1, 1, 1};
Transfinite Curve{:} = 2;
Transfinite Surface{:};
Transfinite Volume{:};
Recombine Surface{:};
Mesh.ElementOrder = 2;
SERENDIPITY
Physical Volume("a") = {1};
Physical Volume("b") = {2};
Physical Volume("c") = {3};
Physical Surface("a_right") = {2};
Physical Surface("b_left") = {7};
"""
BLOCKS_YAML = """dimension: 3
mesh: {geo: case.geo}
materials:
  rubber: {model: neo_hooke, young: 100, poisson: 0.3, density: 1}
bodies:
  - {region: a, material: rubber}
  - {region: b, material: rubber}
  - {region: c, material: rubber}
initial_conditions:
  - {region: a, velocity: ["0.2 - 0.3*(y - 0.5)", "0.3*(x - 0.5)", "0.1"]}
  - {region: b, velocity: ["-0.2", "0.1*(z - 0.6)", "-0.1 - 0.1*(y - 0.7)"]}
interfaces:
  - INTERFACE
time: {integrator: energy_momentum, end: 0.04, steps: 4}
solver: {newton: {tolerance: 1.0e-12, max_iterations: 30}}
output: {every: 1000}
"""
INTERFACES = {
    "two bodies": "{name: impact, type: contact, slave: b_left, master: a_right, MULTIPLIER}",
    "surface": "{name: impact, type: contact, surface: [a_right, b_left], MULTIPLIER}",
}


def two_blocks(faces="quad9", interface="two bodies", multiplier="dual", np=1):
    """The two blocks (quad9: hex27 cells, quad8: hex20) colliding; the energy and momentum
    figures of the run."""
    geo = BLOCKS_GEO.replace("SERENDIPITY", "Mesh.SecondOrderIncomplete = 1;"
                             if faces == "quad8" else "")
    yaml = BLOCKS_YAML.replace("INTERFACE", INTERFACES[interface]).replace(
        "MULTIPLIER", "multiplier: %s" % multiplier)
    rows, itf, newton = R.run_geo(geo, yaml, np)
    e = [r["total_energy"] for r in rows]
    force = [r["normal_force"] for r in itf]
    p0 = [rows[0]["momentum_%s" % c] for c in "xyz"]
    l0 = [rows[0]["angular_momentum_%s" % c] for c in "xyz"]
    scale_p = 0.2  # m |v| of one block
    scale_l = max(math.sqrt(sum(x * x for x in l0)), 2 * scale_p)
    dp = max(abs(r["momentum_%s" % c] - p0[k]) for r in rows
             for k, c in enumerate("xyz")) / scale_p
    dl = max(abs(r["angular_momentum_%s" % c] - l0[k]) for r in rows
             for k, c in enumerate("xyz")) / scale_l
    rise = max(b - a for a, b in zip(e, e[1:])) / e[0]
    persistent = R.persistent_steps(rows, newton)
    change = max([abs(e[k] - e[k - 1]) / e[0] for k in persistent] or [0.0])
    print("   %s faces, %s, %s multipliers, np %d: contact in %d of %d steps, %d persistent; "
          "largest energy rise in a step %.2e, largest change in persistent contact %.2e; "
          "linear momentum kept to %.2e, angular to %.2e (relative)"
          % (faces, interface, multiplier, np, sum(f > 0 for f in force), len(rows),
             len(persistent), rise, change, dp, dl))
    return dict(rows=rows, energy=e, force=force, rise=rise, change=change, dp=dp, dl=dl,
                persistent=persistent)


def check_blocks(r, persistent=2):
    """Contact in 3 steps or more, `persistent` of them persistent; no step gains more than
    1e-10 of the energy; both momenta to 1e-12 of their scales."""
    if sum(f > 0 for f in r["force"]) < 3 or len(r["persistent"]) < persistent:
        raise AssertionError("contact in %d steps, %d persistent: too few"
                             % (sum(f > 0 for f in r["force"]), len(r["persistent"])))
    if r["rise"] > 1e-10 or r["change"] > 1e-10:
        raise AssertionError("a step gained %.3e of the energy; %.3e in persistent contact"
                             % (r["rise"], r["change"]))
    if r["dp"] > 1e-12 or r["dl"] > 1e-12:
        raise AssertionError("momentum drift %.3e, angular %.3e" % (r["dp"], r["dl"]))


def test_quad9_blocks():
    """Two hex27 blocks (quad9 faces), two bodies, dual multipliers, np 1 and 3."""
    r1 = two_blocks()
    check_blocks(r1)
    r3 = two_blocks(np=3)
    check_blocks(r3)
    R.check_np3_equals_np1(r3, r1)


def test_quad9_quad8_blocks_surface():
    """The hex27 blocks as one `surface:` interface (standard multipliers) and the hex20
    blocks (quad8 faces, dual multipliers of the modified basis) between two bodies."""
    # One persistent step here: the roles of the `surface:` pairs are assigned anew.
    check_blocks(two_blocks(interface="surface", multiplier="standard"), persistent=1)
    check_blocks(two_blocks(faces="quad8"))


def newton_check(geo, yaml, at):
    """The central-difference errors of SEAM_NEWTON_CHECK=`at` by step length a:
    (displacement rows, constraint rows), relative to |F| of each."""
    work = tempfile.mkdtemp(prefix="seam_quadratic_")
    H.write_case(work, "case.geo", geo)
    path = H.write_case(work, "case.yaml", yaml)
    os.environ["SEAM_NEWTON_CHECK"] = at
    try:
        code, out, err = H.run(["run", path, "-o", os.path.join(work, "out"), "--quiet"],
                               check=False)
    finally:
        del os.environ["SEAM_NEWTON_CHECK"]
    H.cleanup(work)
    if code != 3:
        raise AssertionError("the Newton check did not run (exit %d): %s" % (code, err[-2000:]))
    central = {}
    for line in out.splitlines():
        m = re.match(r"\s*a = +([0-9.e+-]+) .* central ([0-9.e+-]+) / ([0-9.e+-]+)", line)
        if m:
            central[float(m.group(1))] = (float(m.group(2)), float(m.group(3)))
    return central


def test_quadratic_newton_check():
    """The Newton matrix of the discrete gradient on quad9 faces is the derivative of the
    residual: SEAM_NEWTON_CHECK compares the first correction of a step in persistent contact
    (step 15 of the hex27 ring on the rigid sphere; step 3 of the two hex27 blocks and of the
    same cubes of tet10 cells, tri6 faces with the modified dual basis) with central
    differences of the whole residual along it, whose error falls as a^2: by 1e2 (to 2e-2)
    from a = 0.1 to 0.01 in the displacement and the constraint rows (these relative to |F| of
    the constraint rows, about 1e-17 there: the gaps hold at the start of the iteration), and
    below 1e-8 of |F| in the displacement rows at a = 0.01."""
    geo, yaml = obstacle_case("quad9", "sphere")
    blocks_yaml = BLOCKS_YAML.replace("INTERFACE", INTERFACES["two bodies"]).replace(
        "MULTIPLIER", "multiplier: dual")
    tet10 = BLOCKS_GEO.replace("SERENDIPITY", "").replace("Recombine Surface{:};\n", "")
    for what, case, at in (("ring on the sphere", (geo, yaml), "15:0"),
                           ("two blocks", (BLOCKS_GEO.replace("SERENDIPITY", ""), blocks_yaml),
                            "3:0"),
                           ("two tet10 blocks", (tet10, blocks_yaml), "3:0")):
        central = newton_check(case[0], case[1], at)
        for a in (0.1, 0.01, 0.001):
            print("   %s, a = %.0e: central difference error %.2e (displacement rows), %.2e "
                  "(constraint rows) of |F|" % ((what, a) + central[a]))
        for k in range(2):
            coarse, fine = central[0.1][k], central[0.01][k]
            if not (fine < 2e-2 * coarse and (k == 1 or fine < 1e-8)):
                raise AssertionError("%s: the central differences do not converge to the "
                                     "correction at second order: %.3e at a = 0.1, %.3e at "
                                     "a = 0.01" % (what, coarse, fine))


def test_quadratic_check_names_force():
    """`seam check` names the force of each interface: the discrete gradient on the hex27
    blocks (quad9 faces) and on the hex20 blocks (quad8), with friction on them its normal part
    and the frame-indifferent slip (test_quadratic_friction.py)."""
    cases = (("quad9", "", "discrete gradient of the weighted gaps"),
             ("quad8", "", "discrete gradient of the weighted gaps"),
             ("quad9", "friction: {model: coulomb, coefficient: 0.3}, ",
              "weighted gaps; friction: frame-indifferent slip"))
    for faces, friction, expected in cases:
        geo = BLOCKS_GEO.replace("SERENDIPITY", "Mesh.SecondOrderIncomplete = 1;"
                                 if faces == "quad8" else "")
        yaml = BLOCKS_YAML.replace("INTERFACE", INTERFACES["two bodies"]).replace(
            "MULTIPLIER", friction + "multiplier: dual")
        work = tempfile.mkdtemp(prefix="seam_quadratic_")
        H.write_case(work, "case.geo", geo)
        path = H.write_case(work, "case.yaml", yaml)
        code, out, err = H.run(["check", path])
        H.cleanup(work)
        line = next((l for l in out.splitlines() if "interface impact" in l), "")
        print("   %s%s: %s" % (faces, " with friction" if friction else "", line.strip()[:160]))
        if expected not in line:
            raise AssertionError("seam check does not name '%s' for %s faces%s: %s"
                                 % (expected, faces, " with friction" if friction else "", line))


def test_quadratic_gaps_equal_mortar():
    """The weighted gaps of the energy-momentum kernel (gap_blocks_3d.cpp, `pair_gaps_quadratic`)
    are those of the mortar integration (integration_3d.cpp): the two cubes at rest 0.03
    apart (offset (0.2, 0.1)), one step with energy_momentum (the gaps of the kernel) and with
    generalized_alpha (the mortar's), the gaps of interface_impact.csv equal to 1e-14 on quad9,
    quad8 and tri6 faces (tet10 cells; the dual basis of tri6/quad8 modified)."""
    for faces in ("quad9", "quad8", "tri6"):
        geo = BLOCKS_GEO.replace("Box(2) = {1.002,", "Box(2) = {1.03,").replace(
            "SERENDIPITY", "Mesh.SecondOrderIncomplete = 1;" if faces == "quad8" else "")
        if faces == "tri6":
            geo = geo.replace("Recombine Surface{:};\n", "")
        gaps = {}
        for integrator in ("energy_momentum", "generalized_alpha"):
            yaml = (BLOCKS_YAML.replace("INTERFACE", INTERFACES["two bodies"])
                    .replace("MULTIPLIER", "multiplier: dual")
                    .replace("integrator: energy_momentum", "integrator: " + integrator)
                    .replace("end: 0.04, steps: 4", "end: 0.01, steps: 1")
                    .replace("every: 1000", "every: 1"))
            yaml = "\n".join(l for l in yaml.splitlines() if "velocity" not in l and
                              "initial_conditions" not in l) + "\n"
            work, out = T.run_case(geo, yaml)
            rows = H.read_csv(os.path.join(out, "interface_impact.csv"))
            H.cleanup(work, out)
            gaps[integrator] = [r["gap"] for r in rows]
        a, b = gaps["energy_momentum"], gaps["generalized_alpha"]
        worst = max(abs(x - y) for x, y in zip(a, b))
        print("   %s faces: %d slave nodes, gaps %.4f to %.4f, kernel - mortar at most %.2e"
              % (faces, len(a), min(b), max(b), worst))
        if len(a) != len(b) or max(b) < 0.02 or worst > 1e-14:
            raise AssertionError("%s faces: the kernel's weighted gaps differ from the mortar's "
                                 "by %.3e" % (faces, worst))

if __name__ == "__main__":
    H.main([test_quad9_on_obstacles, test_quad8_tri6_on_obstacles, test_quad9_blocks,
            test_quad9_quad8_blocks_surface, test_quadratic_newton_check,
            test_quadratic_check_names_force, test_quadratic_gaps_equal_mortar])
