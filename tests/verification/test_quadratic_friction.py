"""Coulomb friction in energy-momentum contact on quadratic 3D faces (issue 13;
docs/contact_dynamics.md §5, "Friction").

The normal part of the contact force is the discrete gradient of the weighted gaps of the
quadratic faces (gap_blocks_3d.cpp between bodies, rigid_obstacle_facet.cpp against obstacles);
the tangential part is work conjugate to the slip u~_j = G_j(dx) - theta_j x G_j(x_mid) over
the step's mean mortar operators D, M (against an obstacle u~_j = sum_k D_jk (dx_k - dc)), with
the slave positions of the modified basis x~ = T^-1 x on tri6/quad8 faces (dual multipliers),
the basis their gaps are weighted with. So in persistent contact kinetic + strain energy E
changes by exactly minus the frictional work D of interfaces.csv (E + D constant to the Newton
tolerance), E + D never rises, D never falls, and between bodies the linear and angular momentum
are exact. With the force of the end of the step (main before this change: friction on
quadratic 3D faces fell back to it) the same cases gained energy: figures in each test.
"""
import math
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness as H  # noqa: E402
import test_contact as T  # noqa: E402
import test_quadratic_dynamics as Q  # noqa: E402
import test_rings as R  # noqa: E402
from test_obstacle_dynamics import CYLINDER  # noqa: E402

MU = 0.3
FRICTION = "friction: {model: coulomb, coefficient: %r}, " % MU
ENERGY_BOUND = 1e-10     # of E_0: rise of E + D in a step, change in persistent contact
MOMENTUM_BOUND = 1e-12   # of the momenta's scales
DISSIPATION_ROUND_OFF = 1e-12  # of E_0: the smallest dissipation increment allowed


def energy_figures(rows, itf, newton, label):
    """E = kinetic + strain energy, D = frictional_dissipation; the largest rise of E + D in a
    step and its largest change in persistent contact, the smallest increment of D, relative to
    E_0; the slip and stick node-steps."""
    e = [r["total_energy"] for r in rows]
    d = [r["frictional_dissipation"] for r in itf]
    if len(d) != len(e):
        raise AssertionError("%d rows of interfaces.csv for %d steps" % (len(d), len(e)))
    total = [a + b for a, b in zip(e, d)]
    persistent = R.persistent_steps(rows, newton)
    r = dict(rows=rows, energy=e, dissipation=d, persistent=persistent,
             force=[i["normal_force"] for i in itf],
             rise=max(b - a for a, b in zip(total, total[1:])) / e[0],
             change=max([abs(total[k] - total[k - 1]) / e[0] for k in persistent] or [0.0]),
             increment=min(b - a for a, b in zip(d, d[1:])) / e[0],
             slip=sum(i["slip_nodes"] for i in itf),
             stick=sum(i["active_nodes"] - i["slip_nodes"] for i in itf))
    print("   %s: contact in %d of %d steps, %d persistent; %d stick and %d slip node-steps; "
          "D = %.3e of E_0; largest rise of E + D in a step %.2e, largest change in persistent "
          "contact %.2e; smallest dissipation increment %.1e"
          % (label, sum(f > 0 for f in r["force"]), len(e), len(persistent), r["stick"],
             r["slip"], d[-1] / e[0], r["rise"], r["change"], r["increment"]))
    return r


def check_energy(r, persistent=2):
    """E + D never rises and is constant in persistent contact to ENERGY_BOUND of E_0; D never
    falls; the friction did work (slip node-steps, D > 1e-3 E_0)."""
    if len(r["persistent"]) < persistent:
        raise AssertionError("only %d steps of persistent contact" % len(r["persistent"]))
    if r["slip"] == 0 or r["dissipation"][-1] < 1e-3 * r["energy"][0]:
        raise AssertionError("the friction did no work (%d slip node-steps, D = %.3e)"
                             % (r["slip"], r["dissipation"][-1]))
    if r["rise"] > ENERGY_BOUND or r["change"] > ENERGY_BOUND:
        raise AssertionError("E + D rose by %.3e of E_0 in a step; changed by %.3e in "
                             "persistent contact" % (r["rise"], r["change"]))
    if r["increment"] < -DISSIPATION_ROUND_OFF:
        raise AssertionError("the dissipation fell by %.3e of E_0 in a step" % -r["increment"])


def blocks_case(faces="quad9", interface="two bodies"):
    """The two blocks of test_quadratic_dynamics.py (quad9: hex27, quad8: hex20, tri6: tet10)
    thrown at each other obliquely and spinning, with Coulomb friction mu = 0.3."""
    geo = Q.BLOCKS_GEO.replace("SERENDIPITY", "Mesh.SecondOrderIncomplete = 1;"
                               if faces == "quad8" else "")
    if faces == "tri6":
        geo = geo.replace("Recombine Surface{:};\n", "")
    yaml = Q.BLOCKS_YAML.replace("INTERFACE", Q.INTERFACES[interface]).replace(
        "MULTIPLIER", FRICTION + "multiplier: dual")
    return geo, yaml


def blocks(faces="quad9", interface="two bodies", np=1):
    """blocks_case run: energy_figures and the drift of the linear and angular momentum
    relative to their scales (test_quadratic_dynamics.two_blocks)."""
    rows, itf, newton = R.run_geo(*blocks_case(faces, interface), np)
    r = energy_figures(rows, itf, newton, "%s faces, %s, np %d" % (faces, interface, np))
    p0 = [rows[0]["momentum_%s" % c] for c in "xyz"]
    l0 = [rows[0]["angular_momentum_%s" % c] for c in "xyz"]
    scale_p = 0.2  # m |v| of one block
    scale_l = max(math.sqrt(sum(x * x for x in l0)), 2 * scale_p)
    r["dp"] = max(abs(row["momentum_%s" % c] - p0[k]) for row in rows
                  for k, c in enumerate("xyz")) / scale_p
    r["dl"] = max(abs(row["angular_momentum_%s" % c] - l0[k]) for row in rows
                  for k, c in enumerate("xyz")) / scale_l
    print("   linear momentum kept to %.2e, angular to %.2e (relative)" % (r["dp"], r["dl"]))
    return r


def check_blocks(r, persistent=2):
    """Contact in 3 steps or more, check_energy, both momenta to MOMENTUM_BOUND."""
    if sum(f > 0 for f in r["force"]) < 3:
        raise AssertionError("contact in %d steps only" % sum(f > 0 for f in r["force"]))
    check_energy(r, persistent)
    if r["dp"] > MOMENTUM_BOUND or r["dl"] > MOMENTUM_BOUND:
        raise AssertionError("momentum drift %.3e, angular %.3e" % (r["dp"], r["dl"]))


def check_np3_equals_np1(r3, r1):
    """test_rings.check_np3_equals_np1 and the dissipation to 1e-10 of E_0."""
    R.check_np3_equals_np1(r3, r1)
    dd = max(abs(a - b) for a, b in zip(r1["dissipation"], r3["dissipation"])) / r1["energy"][0]
    print("   np 3 vs np 1: dissipation %.2e of E_0" % dd)
    if dd > 1e-10:
        raise AssertionError("np 3 dissipation differs from np 1 by %.3e" % dd)


def test_quad9_blocks_friction():
    """Two hex27 blocks (quad9 faces), slave/master, dual multipliers, sliding obliquely and
    spinning against each other with mu = 0.3: check_blocks. With the force of the end of the
    step (main) E + D rose by 2.5e-3 of E_0 in a step, the angular momentum by 5.0e-3."""
    check_blocks(blocks())


@H.full_only
def test_quad9_blocks_friction_np3_surface():
    """The hex27 blocks at np 3 (check_blocks, equal to np 1: contact force, energy,
    dissipation) and as one `surface:` interface (one persistent step: the roles of the pairs
    are assigned anew). About 150 s on the loaded machine: SEAM_FULL=1."""
    r1 = blocks()
    r3 = blocks(np=3)
    check_blocks(r3)
    check_np3_equals_np1(r3, r1)
    check_blocks(blocks(interface="surface"), persistent=1)


def test_quad8_blocks_friction():
    """The blocks of hex20 cells (quad8 faces), dual multipliers of the modified basis (the
    slip in the positions x~ = T^-1 x): check_blocks. Their steps count as changes of the set
    (the nodes sliding at the end of a step sit on the cone with a zero slip increment at the
    start of the next one and are held in stick for an iteration): E + D never rising is what
    is checked there. With the force of the end of the step (main) E + D rose by 1.7e-1 of E_0
    in a step, the angular momentum by 9.1e-3."""
    check_blocks(blocks(faces="quad8"), persistent=0)


def test_tri6_blocks_friction():
    """The same with tet10 cells (tri6 faces, modified dual basis). With the force of the end
    of the step (main) E + D rose by 5.8e-2 of E_0 in a step, the angular momentum by 1.6e-2."""
    check_blocks(blocks(faces="tri6"), persistent=0)


def obstacle_case(body, obstacle):
    """The hex27 ring (quad9), the hex20 ring (quad8) or the tet10 ball (tri6) of
    test_quadratic_dynamics.py thrown
    obliquely and spinning onto a rigid plane or sphere, mu = 0.3, dual multipliers."""
    geo, yaml = Q.obstacle_case(body, obstacle)
    return geo, yaml.replace("multiplier: dual,", FRICTION + "multiplier: dual,")


def test_friction_on_obstacles():
    """The hex20 ring (quad8 faces, modified dual basis) onto the rigid plane and the hex27 ring
    (quad9 faces) onto the rigid sphere and cylinder, mu = 0.3: check_energy (on the plane no step is
    persistent: the ring rolls onto new nodes and the sliding nodes, exactly on the cone at the
    start of a step, count as changes in its first iteration; E + D never rising is checked
    there). On the plane (normal y) the tangential contact force lies in the plane: each step's
    tangential impulse (the change of the momentum along the plane) is at most mu times the
    normal one (the change of p_y; 2 % for the mean operators against the discrete gradient)
    and the friction brakes the sliding (p_x falls); np 3 (the ring's slave side split over the
    ranks) equals np 1. With the force of the end of the step (main) E + D rose by 3.7e-5 of
    E_0 in a step on the sphere (1.9e-4 in a persistent step), 2.9e-6 on the cylinder (1.7e-5;
    on the plane, with dual multipliers, 3.5e-12: consistent already)."""
    rows, itf, newton = R.run_geo(*obstacle_case("quad8", "plane"), 1)
    r1 = energy_figures(rows, itf, newton, "quad8 faces on the rigid plane")
    check_energy(r1, persistent=0)
    r3 = energy_figures(*R.run_geo(*obstacle_case("quad8", "plane"), 3),
                        "quad8 faces on the rigid plane, np 3")
    check_energy(r3, persistent=0)
    check_np3_equals_np1(r3, r1)
    worst, braked, steps = 0.0, 0, 0
    for a, b, i in zip(rows, rows[1:], itf[1:]):
        dn = b["momentum_y"] - a["momentum_y"]
        dt = math.hypot(b["momentum_x"] - a["momentum_x"], b["momentum_z"] - a["momentum_z"])
        if i["active_nodes"] > 0 and dn > 1e-3 * abs(rows[0]["momentum_y"]):
            steps += 1
            worst = max(worst, dt / (MU * dn))
            braked += b["momentum_x"] < a["momentum_x"]
    print("   tangential impulse / (mu normal impulse) at most %.4f; p_x fell in %d of %d steps "
          "with a normal impulse" % (worst, braked, steps))
    if not 0.5 < worst < 1.02 or braked < 5:
        raise AssertionError("friction impulse: %.4f of mu times the normal one, p_x fell in %d "
                             "steps" % (worst, braked))
    rows, itf, newton = R.run_geo(*obstacle_case("quad9", "sphere"), 1)
    check_energy(energy_figures(rows, itf, newton, "quad9 faces on the rigid sphere"),
                 persistent=10)
    R.OBSTACLES.setdefault("cylinder", {3: CYLINDER})
    rows, itf, newton = R.run_geo(*obstacle_case("quad9", "cylinder"), 1)
    check_energy(energy_figures(rows, itf, newton, "quad9 faces on the rigid cylinder"),
                 persistent=10)


def test_restart_quadratic_friction_np3():
    """The hex20 ring on the rigid sphere (quad8 faces, modified basis) with a checkpoint every
    5 steps, continued from the checkpoint of step 15 (sliding) on 3 ranks: the step's mean
    operators need the last converged step's D (the checkpoint's friction history), the slip
    T^-1 of the side split over the ranks. Energy and dissipation of the continued steps equal
    the uninterrupted run's to 1e-10 of E_0, and E + D never rises in them by more than
    ENERGY_BOUND of the energy. With the force of the end of the step (main) E + D rose by
    7.6e-5 of the energy in a continued step."""
    import test_friction_dynamics as FD
    geo, yaml = obstacle_case("quad8", "sphere")
    yaml = yaml.replace("output: {every: 1000}", "output: {every: 1000, checkpoint_every: 5}")
    work = tempfile.mkdtemp(prefix="seam_quadratic_friction_")
    H.write_case(work, "case.geo", geo)
    path = H.write_case(work, "case.yaml", yaml)
    b, bi, de, dd = FD.continued_on_3_ranks(work, path, "checkpoint_00015")
    slipping = sum(bi[k]["slip_nodes"] > 0 for k in bi)
    total = [b[k]["total_energy"] + bi[k]["frictional_dissipation"] for k in sorted(b)]
    rise = max(y - x for x, y in zip(total, total[1:])) / total[0]
    print("   restart from step 15 on 3 ranks: %d steps (%d with slip), energy %.2e, "
          "dissipation %.2e of E_0; largest rise of E + D in a continued step %.2e"
          % (len(b), slipping, de, dd, rise))
    if len(b) < 15 or slipping == 0 or de > 1e-10 or dd > 1e-10 or rise > ENERGY_BOUND:
        raise AssertionError("restart: %d steps, %d with slip, energy %.3e, dissipation %.3e, "
                             "rise of E + D %.3e" % (len(b), slipping, de, dd, rise))


# A hex20 block (quad8 faces, modified dual basis), 2 x 1 x 2 cells of 1 x 0.5 x 1, resting on
# the rigid plane y = 0 under a gravity g = 10 tilted by the angle alpha about z (the plane
# inclined by alpha), ramped in over 0.1 and held to 0.6.
STICK_GEO = """SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 0.5, 1};
Transfinite Curve{:} = 3;
Transfinite Surface{:};
Transfinite Volume{:};
Recombine Surface{:};
Mesh.ElementOrder = 2;
Mesh.SecondOrderIncomplete = 1;
Physical Volume("block") = {1};
Physical Surface("bottom") = {3};
"""
STICK_YAML = """dimension: 3
mesh: {geo: case.geo}
materials:
  m: {model: neo_hooke, young: 1000, poisson: 0.3, density: 1}
bodies:
  - {region: block, material: m}
boundary_conditions:
  - {region: block, type: body_force, value: ["GX*min(t/0.1, 1)", "-GY*min(t/0.1, 1)", "0"]}
interfaces:
  - {name: floor, type: contact, slave: bottom, FRICTION multiplier: dual,
     rigid_plane: {point: [0, 0, 0], normal: [0, 1, 0]}}
time: {integrator: energy_momentum, end: 0.6, steps: 30}
solver: {newton: {tolerance: 1.0e-10, max_iterations: 30}}
output: {every: 1000, probes: [[0.5, 0, 0.5], [0, 0, 0], [1, 0, 0], [0, 0, 1], [1, 0, 1], [0.5, 0, 0]]}
"""


def check_names_force(geo, yaml, expected):
    """`seam check` names `expected` in the line of the case's interface: the run takes the
    energy-momentum force with friction (main named the force of the end of the step)."""
    work = tempfile.mkdtemp(prefix="seam_quadratic_friction_")
    H.write_case(work, "case.geo", geo)
    path = H.write_case(work, "case.yaml", yaml)
    code, out, err = H.run(["check", path])
    H.cleanup(work)
    line = next((l for l in out.splitlines() if "interface " in l and "contact" in l), "")
    print("   seam check: %s" % line.strip()[:200])
    if expected not in line:
        raise AssertionError("seam check does not name '%s': %s" % (expected, line))


def on_incline(tan_alpha):
    """The block on the plane inclined by alpha: the largest |u_x| of the bottom's probes (its
    centre, corners and an edge midpoint) over the run and their largest motion along the plane
    after the ramp (from t = 0.2 on), the slip node-steps."""
    g = 10.0
    c = 1.0 / math.sqrt(1.0 + tan_alpha ** 2)
    yaml = (STICK_YAML.replace("GX", repr(g * tan_alpha * c)).replace("GY", repr(g * c))
            .replace("FRICTION", FRICTION))
    work, out = T.run_case(STICK_GEO, yaml)
    probes = H.read_csv(os.path.join(out, "probes.csv"))
    itf = H.read_csv(os.path.join(out, "interfaces.csv"))
    H.cleanup(work, out)
    settled = {p["probe"]: p["ux"] for p in probes if abs(p["time"] - 0.2) < 1e-9}
    last = max(p["step"] for p in probes)
    after = max(abs(p["ux"] - settled[p["probe"]]) for p in probes if p["step"] == last)
    most = max(abs(p["ux"]) for p in probes)
    slip = sum(i["slip_nodes"] for i in itf)
    print("   tan(alpha) = %.2f (mu = %.2f): %d of %d active node-steps slip; |u_x| of the bottom "
          "at most %.3e, its motion from t = 0.2 to 0.6 %.3e"
          % (tan_alpha, MU, slip, sum(i["active_nodes"] for i in itf), most, after))
    return most, after, slip


def test_stick_on_incline():
    """The hex20 block on a plane inclined below the friction angle (tan alpha = 0.2 < mu)
    sticks: once the gravity is in (t >= 0.2) the bottom moves along the plane by less than
    1e-4 of what it slides above the friction angle (tan alpha = 0.45) in the same time, and
    over the whole run (the edges slip a little while the load comes in, as an elastic block's
    edges do) by less than 1e-2 of it. Above the friction angle the block slides by more than
    0.05. `seam check` names the energy-momentum force with friction for the case (main: the
    force of the end of the step, which sticks as well: this test fails on main only there)."""
    check_names_force(STICK_GEO, STICK_YAML.replace("GX", "1").replace("GY", "10")
                      .replace("FRICTION", FRICTION), "friction: slip over the step's mean D")
    most, after, _ = on_incline(0.2)
    _, after_slide, slip_slide = on_incline(0.45)
    if slip_slide == 0 or after_slide < 0.05:
        raise AssertionError("above the friction angle the block does not slide: %d slip "
                             "node-steps, %.3e from t = 0.2 on" % (slip_slide, after_slide))
    if after > 1e-4 * after_slide or most > 1e-2 * after_slide:
        raise AssertionError("below the friction angle the bottom moved by %.3e after the "
                             "ramp, %.3e in all" % (after, most))


def test_quadratic_friction_newton_check():
    """The Newton matrix of friction on quadratic faces is the derivative of the residual:
    SEAM_NEWTON_CHECK at a correction of a slipping step in persistent contact (step 3 of the
    hex27 blocks and of the tet10 blocks, tri6 faces with the modified basis, every node
    slipping, first correction; step 15 of the hex20 ring on the plane, quad8 faces with the
    modified basis, second correction: in the first the sliding nodes, on the cone with a zero
    slip increment, are held in stick and the constraint rows are linear along it): the central
    differences' error falls as a^2, by 1e2 (to 2e-2) from a = 0.1 to 0.01 in the displacement
    and the constraint rows, and is below `bound` of |F| in the displacement rows at a = 0.01
    (1e-8 at a first correction, 1e-5 at the second, whose |F| is the Newton step's residual)."""
    for what, case, at, bound in (
            ("hex27 blocks", blocks_case("quad9"), "3:0", 1e-8),
            ("tet10 blocks", blocks_case("tri6"), "3:0", 1e-8),
            ("hex20 ring on the plane", obstacle_case("quad8", "plane"), "15:1", 1e-5)):
        central = Q.newton_check(case[0], case[1], at)
        for a in (0.1, 0.01, 0.001):
            print("   %s, a = %.0e: central difference error %.2e (displacement rows), %.2e "
                  "(constraint rows) of |F|" % ((what, a) + central[a]))
        for k in range(2):
            coarse, fine = central[0.1][k], central[0.01][k]
            if not (fine < 2e-2 * coarse and (k == 1 or fine < bound)):
                raise AssertionError("%s: the central differences do not converge to the "
                                     "correction at second order: %.3e at a = 0.1, %.3e at "
                                     "a = 0.01" % (what, coarse, fine))


if __name__ == "__main__":
    H.main([test_quad9_blocks_friction, test_quad9_blocks_friction_np3_surface,
            test_quad8_blocks_friction, test_tri6_blocks_friction,
            test_friction_on_obstacles, test_restart_quadratic_friction_np3,
            test_stick_on_incline,
            test_quadratic_friction_newton_check])
