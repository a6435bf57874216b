"""Convergence of mortar mesh tying on non-matching meshes (issue: mortar mesh tying).

The manufactured solution of test_convergence.py (linear elasticity, E = 1, nu = 0.3,
u = (sin(a x) cos(b y) [cos(c z)], 0 [, 0]) with its body force) on two stacked bodies whose
meshes do not match at the interface; either side coarser. Over four refinements the L2 and H1
slopes of the displacement must be those of conforming meshes (p + 1 and p), and the
multiplier at the slave nodes must converge to the exact interface traction:
lambda = -t_slave = sigma . e_y on the interface y = 1 (the slave's outward normal is -e_y).
"""
import math
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import geometry  # noqa: E402
import harness as H  # noqa: E402
from test_convergence import A, B, LAM, MU, fields  # noqa: E402


def case_yaml(dim, slave, master, multiplier, strategy):
    exact, force = fields(dim)
    q = lambda v: "[" + ", ".join("'%s'" % e for e in v) + "]"  # noqa: E731
    # Dirichlet on top and bottom; the exact traction on the sides, so that the interface ends
    # carry multipliers (an end node with a Dirichlet condition would need the crosspoint
    # modification of the dual basis).
    faces = ["bottom", "top"]
    lines = ["dimension: %d" % dim,
             "mesh: {geo: body.geo}",
             "materials: {m: {model: linear_elastic, young: 1, poisson: 0.3}}",
             "bodies: [{region: lower, material: m}, {region: upper, material: m}]",
             "boundary_conditions:"]
    lines += ["  - {region: %s, type: dirichlet, value: %s}" % (f, q(exact)) for f in faces]
    sxx = "%.17g*cos(%g*x)*cos(%g*y)" % ((LAM + 2 * MU) * A, A, B)
    sxy = "%.17g*sin(%g*x)*sin(%g*y)" % (-MU * B, A, B)
    lines += ["  - {region: left, type: traction, value: ['-(%s)', '-(%s)']}" % (sxx, sxy),
              "  - {region: right, type: traction, value: ['%s', '%s']}" % (sxx, sxy)]
    lines += ["  - {region: %s, type: body_force, value: %s}" % (b, q(force)) for b in ("lower", "upper")]
    lines += ["interfaces:",
              "  - {name: tie, type: mesh_tying, slave: %s, master: %s, multiplier: %s, strategy: %s}"
              % (slave, master, multiplier, strategy),
              "time: {integrator: static, end: 1, steps: 1}",
              "output: {exact_displacement: %s}" % q(exact)]
    return "\n".join(lines) + "\n"


def multiplier_error(out):
    """RMS over the tied slave nodes of lambda - sigma . e_y (2D, interface y = 1)."""
    total, n = 0.0, 0
    for r in H.read_csv(os.path.join(out, "interface_tie.csv")):
        if r["status"] != "tied":
            continue
        x = r["x"]
        sxy = -MU * B * math.sin(A * x) * math.sin(B * 1.0)
        syy = LAM * A * math.cos(A * x) * math.cos(B * 1.0)
        # normal_traction = lambda . n with n = -e_y; tangential = |lambda_x|
        total += (r["normal_traction"] + syy) ** 2 + (r["tangential_traction"] - abs(sxy)) ** 2
        n += 1
    return math.sqrt(total / n)


def study(order, ratio, slave, master, expect, multiplier="dual", strategy="condensed", np=1,
          sizes=(0.25, 0.125, 0.0625, 0.03125)):
    hs, l2, h1, lm = [], [], [], []
    for h in sizes:
        work = tempfile.mkdtemp(prefix="seam_tconv_")
        kind = "tri"
        H.write_case(work, "body.geo", geometry.tied_rectangles(h, ratio * h, order, kind))
        yaml = H.write_case(work, "case.yaml", case_yaml(2, slave, master, multiplier, strategy))
        out = H.solve(yaml, np=np)
        err = H.read_csv(os.path.join(out, "errors.csv"))[-1]
        hs.append(h)
        l2.append(err["l2_error"])
        h1.append(err["h1_error"])
        lm.append(multiplier_error(out))
        H.cleanup(out, work)
    # The rates of the three finest levels: the coarsest level of the coarser body has only
    # two or three elements across and is not yet asymptotic.
    s = (H.slope(hs[1:], l2[1:]), H.slope(hs[1:], h1[1:]), H.slope(hs[1:], lm[1:]))
    print("order %d, upper/lower size ratio %g, slave %s, %s %s:" % (order, ratio, slave, multiplier, strategy))
    print("   L2 %s slope %.3f" % (" ".join("%.3e" % e for e in l2), s[0]))
    print("   H1 %s slope %.3f" % (" ".join("%.3e" % e for e in h1), s[1]))
    print("   multiplier RMS %s slope %.3f" % (" ".join("%.3e" % e for e in lm), s[2]))
    if abs(s[0] - expect[0]) > 0.2 or abs(s[1] - expect[1]) > 0.2 or s[2] < expect[2]:
        raise AssertionError("slopes %s, expected about %s (multiplier at least %g)" % (s, expect[:2], expect[2]))


def test_linear_slave_finer(): study(1, 0.6, "upper_bottom", "lower_top", (2, 1, 0.9))
def test_linear_slave_coarser(): study(1, 1.6, "upper_bottom", "lower_top", (2, 1, 0.9))
def test_linear_saddle_standard(): study(1, 0.6, "upper_bottom", "lower_top", (2, 1, 0.9), "standard", "saddle_point")
def test_quadratic_slave_finer(): study(2, 0.6, "upper_bottom", "lower_top", (3, 2, 1.4), sizes=(0.5, 0.25, 0.125, 0.0625))
def test_quadratic_slave_coarser_np3(): study(2, 1.6, "upper_bottom", "lower_top", (3, 2, 1.4), np=3, sizes=(0.25, 0.125, 0.0625, 0.03125))


if __name__ == "__main__":
    H.main([test_linear_slave_finer, test_linear_slave_coarser, test_linear_saddle_standard,
            test_quadratic_slave_finer, test_quadratic_slave_coarser_np3])
