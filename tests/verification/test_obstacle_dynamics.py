"""Energy-momentum contact against a rigid cylinder (issue 13; docs/contact_dynamics.md §5;
friction against rigid obstacles: test_obstacle_friction.py).

The ring of test_rings.py extruded by 0.5 along z (6 cells per quarter circle, 2 through the
wall, hexahedra: quad4 faces), thrown obliquely (v = (0.4, -1, 0.1)) and spinning (0.5 about
z) onto a rigid cylinder of radius 6 whose axis a = (1, 0, 0.3) / |.| runs through
c = (0, -6, 0.25) under it, with `integrator: energy_momentum`. The weighted gap of a slave
node against the cylinder, g~_j = int Phi_j (|P (x - c)| - R) da (P = I - a a^T), does not
change when the slave nodes slide along a or turn about the axis; its discrete gradient is free
of force along a and of moment about the axis (the correction's direction leaves those motions
out), so of all the momenta only two are conserved by the contact:
- the momentum along the axis, a . p, and
- the angular momentum about the axis, a . (L - c x p) (L about the origin, from steps.csv).
The other components change by the cylinder's reaction. Checked: no step gains more than 1e-8
of the energy (Newton tolerance 1e-12) and in the steps of persistent contact it changes by
less than 1e-8; both conserved components stay to 1e-12 of m |v| (and m |v| R); np = 3 equals
np = 1 (contact force to 1e-8, energy to 1e-10); and, to show the test can fail, the
components that are not conserved do change (by more than 1e-3 of their scale).
With the force of the end of the step (the build before this one) the same case gained up to
4.4e-4 (dual) and 6.1e-3 (standard) of the energy in a step, and its angular momentum about the
axis drifted by 9.5e-5 (the momentum along the axis was kept: that force is normal to the
cylinder); measured with SEAM set to that build, docs/contact_dynamics.md §5.
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness as H  # noqa: E402
import test_rings as R  # noqa: E402

AXIS = (1.0, 0.0, 0.3)
POINT = (0.0, -6.0, 0.25)
CYLINDER = "rigid_cylinder: {point: [0, -6, 0.25], axis: [1, 0, 0.3], radius: 6}"


def unit(v):
    n = math.sqrt(sum(x * x for x in v))
    return tuple(x / n for x in v)


def components(q):
    """(a . p, a . (L - c x p)) of a row of steps.csv, and the momentum normal to a in the
    plane of a and z' (not conserved: the reaction's part)."""
    a = unit(AXIS)
    p = [q["momentum_%s" % k] for k in "xyz"]
    l = [q["angular_momentum_%s" % k] for k in "xyz"]
    c = POINT
    cxp = (c[1] * p[2] - c[2] * p[1], c[2] * p[0] - c[0] * p[2], c[0] * p[1] - c[1] * p[0])
    along = sum(a[k] * p[k] for k in range(3))
    about = sum(a[k] * (l[k] - cxp[k]) for k in range(3))
    return along, about, p[1]


def ring_on_cylinder(multiplier="dual", np=1, steps=40):
    R.OBSTACLES.setdefault("cylinder", {3: CYLINDER})
    return R.ring_on_obstacle(3, "cylinder", multiplier=multiplier, np=np, n=6, steps=steps)


def check_cylinder(r):
    rows = r["rows"]
    R.check_obstacle_energy(r)
    m = math.pi * (1.0 - 0.36) * 0.5
    scale = m * (1.0 + 0.4 ** 2 + 0.1 ** 2) ** 0.5
    first = components(rows[0])
    along = max(abs(components(q)[0] - first[0]) for q in rows) / scale
    about = max(abs(components(q)[1] - first[1]) for q in rows) / (scale * 7)
    normal = max(abs(components(q)[2] - first[2]) for q in rows) / scale
    print("   momentum along the axis kept to %.2e, angular momentum about the axis to %.2e "
          "(relative); the momentum along y (not conserved) changed by %.2e"
          % (along, about, normal))
    if along > 1e-12 or about > 1e-12:
        raise AssertionError("the conserved components drift: %.3e along, %.3e about the axis"
                             % (along, about))
    if normal < 1e-3:
        raise AssertionError("the cylinder's reaction did not change the momentum along y "
                             "(%.3e): the check of the conserved parts proves nothing" % normal)


def test_ring_on_cylinder():
    """A ring extruded onto a rigid cylinder with energy_momentum, dual multipliers at np 1 and
    3, standard at np 1: check_cylinder; np 3 equals np 1."""
    r1 = ring_on_cylinder()
    check_cylinder(r1)
    r3 = ring_on_cylinder(np=3)
    check_cylinder(r3)
    R.check_np3_equals_np1(r3, r1)
    check_cylinder(ring_on_cylinder(multiplier="standard"))
    print("   for comparison, the force of the end of the step (the build before, measured): "
          "largest energy rise in a step 4.4e-4 (dual), 6.1e-3 (standard); angular momentum "
          "about the axis 9.5e-5")


if __name__ == "__main__":
    H.main([test_ring_on_cylinder])
