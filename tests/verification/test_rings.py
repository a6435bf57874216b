"""Free bodies colliding through one `surface:` interface, and the rings example (issue 13).

- Free bodies: two Neo-Hooke rings (2D annuli of quads; 3D the annuli extruded into
  hexahedra), no Dirichlet conditions, flying at each other off-centre with initial velocities
  that have a rotation component (v = v0 + w x (X - c)), one `surface:` interface over both
  whole boundaries, implicit dynamics (generalized-alpha and energy-momentum). Without
  external loads the linear momentum sum (M v)_a and the angular momentum sum x_a x (M v)_a
  are constant: the linear momentum must stay within 1e-12 of the momentum scale (m |v| of
  one ring) through the impact, the angular momentum within 1e-12 before it; the bodies must
  touch; np = 3 equals np = 1. What the impact still does to the angular momentum and the
  energy is measured and printed (see test_free_bodies_2d).
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness as H  # noqa: E402
import test_contact as T  # noqa: E402


def ring_geo(centres, nc, nr, radius=1.0, inner=0.6):
    """Gmsh text of annuli (transfinite quads, nc cells per quarter circle, nr through the
    wall) at the given centres: physical surfaces r0, r1, ... and curves r0_boundary, ...
    (inner and outer circles)."""
    lines = ["nc = %d; nr = %d; R = %r; r = %r;" % (nc, nr, radius, inner)]
    for i, (cx, cy) in enumerate(centres):
        o = 100 * i  # tag offset of ring i
        lines.append("cx = %r; cy = %r;" % (cx, cy))
        lines.append("Point(%d) = {cx, cy, 0};" % (o + 1))
        for k, (dx, dy) in enumerate(((1, 0), (0, 1), (-1, 0), (0, -1))):
            lines.append("Point(%d) = {cx + %d * R, cy + %d * R, 0};" % (o + 2 + k, dx, dy))
            lines.append("Point(%d) = {cx + %d * r, cy + %d * r, 0};" % (o + 6 + k, dx, dy))
        for k in range(4):
            k1 = (k + 1) % 4
            lines.append("Circle(%d) = {%d, %d, %d};" % (o + 1 + k, o + 2 + k, o + 1, o + 2 + k1))
            lines.append("Circle(%d) = {%d, %d, %d};" % (o + 5 + k, o + 6 + k, o + 1, o + 6 + k1))
            lines.append("Line(%d) = {%d, %d};" % (o + 9 + k, o + 6 + k, o + 2 + k))
        for k in range(4):
            k1 = (k + 1) % 4
            lines.append("Curve Loop(%d) = {%d, %d, %d, %d}; Plane Surface(%d) = {%d};"
                         % (o + 1 + k, o + 9 + k, o + 1 + k, -(o + 9 + k1), -(o + 5 + k),
                            o + 1 + k, o + 1 + k))
        lines.append("Transfinite Curve{%d:%d} = nc + 1; Transfinite Curve{%d:%d} = nr + 1;"
                     % (o + 1, o + 8, o + 9, o + 12))
        lines.append("Transfinite Surface{%d:%d}; Recombine Surface{%d:%d};"
                     % (o + 1, o + 4, o + 1, o + 4))
        lines.append('Physical Surface("r%d") = {%d:%d};' % (i, o + 1, o + 4))
        lines.append('Physical Curve("r%d_boundary") = {%d:%d};' % (i, o + 1, o + 8))
    return "\n".join(lines) + "\n"


def ring_geo_3d(centres, nc, nr, thickness=0.5):
    """The annuli of ring_geo extruded by `thickness` in z (one layer of hexahedra): physical
    volumes r0, r1, ... and surfaces r0_boundary, ... (all faces of each)."""
    geo = ring_geo(centres, nc, nr)
    keep = [line for line in geo.splitlines() if not line.startswith("Physical")]
    for i in range(len(centres)):
        o = 100 * i
        keep.append("e%d[] = Extrude {0, 0, %r} { Surface{%d:%d}; Layers{1}; Recombine; };"
                    % (i, thickness, o + 1, o + 4))
        # Extrude returns per surface: top, volume, then the four lateral faces.
        keep.append('Physical Volume("r%d") = {e%d[1], e%d[7], e%d[13], e%d[19]};'
                    % ((i,) + (i,) * 4))
        keep.append('Physical Surface("r%d_boundary") = {%d:%d, e%d[0], e%d[6], e%d[12], '
                    'e%d[18], e%d[3], e%d[5], e%d[9], e%d[11], e%d[15], e%d[17], e%d[21], '
                    'e%d[23]};' % ((i, o + 1, o + 4) + (i,) * 12))
    return "\n".join(keep) + "\n"


# Ring a at the origin, ring b beyond a gap of 0.1 and 0.6 higher, so the impact is eccentric
# and changes the spin of both.
CENTRES = ((0.0, 0.0), (2.1, 0.6))

# E = 100, rho = 1 (c ~ 10): a flies at 0.5 and spins at 0.3 about its centre, b comes at
# -0.5 spinning the other way; they touch near t = 0.1.
FREE_YAML = """dimension: DIM
mesh: {geo: case.geo}
SETFACTORY
materials:
  rubber: {model: neo_hooke, young: 100, poisson: 0.3, density: 1}
bodies:
  - {region: r0, material: rubber}
  - {region: r1, material: rubber}
initial_conditions:
  - {region: r0, velocity: [VA]}
  - {region: r1, velocity: [VB]}
interfaces:
  - {name: impact, type: contact, surface: [r0_boundary, r1_boundary]}
time: {integrator: INTEGRATOR, end: 0.4, steps: STEPS}
solver: {newton: {tolerance: 1.0e-12, max_iterations: 30}}
output: {every: 1000}
"""
VELOCITIES = {
    2: ('"0.5 - 0.3*y", "0.3*x"', '"-0.5 + 0.2*(y - 0.6)", "-0.2*(x - 2.1)"'),
    3: ('"0.5 - 0.3*y", "0.3*x", "0.1"', '"-0.5 + 0.2*(y - 0.6)", "-0.2*(x - 2.1)", "-0.1"'),
}

# Linear momentum: the contact forces D_jj lambda_j n_j on a slave node and -M_jk lambda_j n_j
# on the master nodes cancel (the rows of M sum to D_jj), so both integrators keep it to
# round-off.
MOMENTUM_BOUND = 1e-12

def free_bodies(dimension, integrator, np=1, n=4, steps=40):
    va, vb = VELOCITIES[dimension]
    yaml = (FREE_YAML.replace("DIM", str(dimension)).replace("VA", va).replace("VB", vb)
            .replace("INTEGRATOR", integrator).replace("STEPS", str(steps))
            .replace("SETFACTORY\n", ""))
    geo = ring_geo(CENTRES, n, 2) if dimension == 2 else ring_geo_3d(CENTRES, n, 2)
    work, out = T.run_case(geo, yaml, np=np)
    rows = H.read_csv(os.path.join(out, "steps.csv"))
    itf = H.read_csv(os.path.join(out, "interfaces.csv"))
    H.cleanup(work, out)
    first = rows[0]
    p0 = [first["momentum_%s" % c] for c in "xyz"]
    l0 = [first["angular_momentum_%s" % c] for c in "xyz"]
    scale_p = sum(x * x for x in p0) ** 0.5
    # |p0| is small (the bodies fly at each other); the momentum scale is that of one body,
    # m |v| = 0.5 per unit volume, and of its angular momentum about the origin.
    scale_p = max(scale_p, 0.5)
    scale_l = max(sum(x * x for x in l0) ** 0.5, scale_p * 2.0)
    dp = max(abs(r["momentum_%s" % c] - p0[k]) for r in rows for k, c in enumerate("xyz"))
    dl = max(abs(r["angular_momentum_%s" % c] - l0[k]) for r in rows
             for k, c in enumerate("xyz"))
    e = [r["total_energy"] for r in rows]
    rise = max(b - a for a, b in zip(e, e[1:])) / e[0]
    force = [r["normal_force"] for r in itf]
    print("   %dD %s np %d: contact in %d of %d steps (peak force %.4g); linear momentum "
          "drift %.2e, angular %.2e (relative); energy end/start %.8f, largest rise in a "
          "step %.2e" % (dimension, integrator, np, sum(f > 0 for f in force), len(rows),
                         max(force), dp / scale_p, dl / scale_l, e[-1] / e[0], rise))
    if not any(f > 0 for f in force):
        raise AssertionError("the bodies never touched")
    return dict(dp=dp / scale_p, dl=dl / scale_l, rise=rise, force=force, energy=e,
                dl_free=angular_before_contact(rows, force) / scale_l)


def angular_before_contact(rows, force):
    """Angular momentum drift over the steps before the first contact force, relative."""
    first = next(k for k, f in enumerate(force) if f > 0.0)
    free = rows[:first]
    l0 = [rows[0]["angular_momentum_%s" % c] for c in "xyz"]
    return max(abs(r["angular_momentum_%s" % c] - l0[k]) for r in free
               for k, c in enumerate("xyz"))


def check_free(r, integrator):
    if r["dp"] > MOMENTUM_BOUND:
        raise AssertionError("linear momentum drift %.3e > %.0e" % (r["dp"], MOMENTUM_BOUND))
    if integrator == "energy_momentum" and r["dl_free"] > 1e-12:
        raise AssertionError("angular momentum drift %.3e before the contact" % r["dl_free"])


def test_free_bodies_2d():
    """Two rings (32 x 2 quads each). Linear momentum to 1e-12 (both integrators), angular
    momentum to 1e-12 before the contact (energy-momentum scheme), np = 3 equals np = 1.

    Not met yet (issue 13 asks for both): through the contact the angular momentum drifts by
    5e-4 of its scale and single steps of the energy-momentum scheme gain up to 5e-4 of the
    energy (16 x 2 quads per ring: 3e-3 and 8e-2). The contact forces act at the end of the
    step, torque-free about x_{n+1}, while the midpoint balance takes their moment about
    x_{n+1/2}; the drift does not fall cleanly with dt (40 -> 80 steps: 5.2e-4 -> 3.0e-4), so
    the faceted contact surface contributes as well."""
    for integrator in ("generalized_alpha", "energy_momentum"):
        r1 = free_bodies(2, integrator, n=8)
        check_free(r1, integrator)
    r3 = free_bodies(2, "energy_momentum", n=8, np=3)
    worst = max(abs(a - b) for a, b in zip(r3["force"], r1["force"])) / max(r1["force"])
    dl = abs(r3["dl"] - r1["dl"]) / r1["dl"]
    print("   np 3 vs np 1: contact force max rel. diff %.2e, angular drift rel. diff %.2e"
          % (worst, dl))
    if worst > 1e-8 or len(r3["force"]) != len(r1["force"]) or dl > 1e-6:
        raise AssertionError("np 3 differs from np 1 by %.3e" % worst)


def test_free_bodies_3d():
    """The two rings extruded by 0.5 (24 x 2 x 1 hexahedra each), sliding past each other in
    z as well: linear momentum to 1e-12 with both integrators, angular momentum to 1e-12
    before the contact. Not met yet: through the contact the angular momentum drifts by 8e-3
    and single steps gain up to 2e-3 of the energy (16 x 2 x 1 hexahedra: 18 %)."""
    for integrator in ("generalized_alpha", "energy_momentum"):
        check_free(free_bodies(3, integrator, n=6, steps=20), integrator)


if __name__ == "__main__":
    H.main([test_free_bodies_2d, test_free_bodies_3d])
