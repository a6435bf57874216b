"""Convergence under mesh refinement with a manufactured solution (issue: foundation).

Linear elasticity (E = 1, nu = 0.3) with the exact displacement

    2D (plane strain):  u = (sin(a x) cos(b y), 0)
    3D:                 u = (sin(a x) cos(b y) cos(c z), 0, 0)

prescribed on the whole boundary, and the body force f = -(mu lap u + (lambda + mu) grad div u):

    f_x = [mu (a^2 + b^2 (+ c^2)) + (lambda + mu) a^2] sin(a x) cos(b y) (cos(c z))
    f_y = (lambda + mu) a b cos(a x) sin(b y) (cos(c z))
    f_z = (lambda + mu) a c cos(a x) cos(b y) sin(c z)

seam reports the L2 and H1 errors (output.exact_displacement -> errors.csv). Over four
uniform refinements the slopes must be about p + 1 (L2) and p (H1) for elements of order p.
"""
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import geometry  # noqa: E402
import harness as H  # noqa: E402

E, NU = 1.0, 0.3
MU = E / (2 * (1 + NU))
LAM = E * NU / ((1 + NU) * (1 - 2 * NU))
A, B, C = 1.3, 0.9, 0.7


def fields(dim):
    if dim == 2:
        exact = ["sin(%g*x)*cos(%g*y)" % (A, B), "0"]
        force = ["%.17g*sin(%g*x)*cos(%g*y)" % (MU * (A * A + B * B) + (LAM + MU) * A * A, A, B),
                 "%.17g*cos(%g*x)*sin(%g*y)" % ((LAM + MU) * A * B, A, B)]
    else:
        exact = ["sin(%g*x)*cos(%g*y)*cos(%g*z)" % (A, B, C), "0", "0"]
        force = ["%.17g*sin(%g*x)*cos(%g*y)*cos(%g*z)"
                 % (MU * (A * A + B * B + C * C) + (LAM + MU) * A * A, A, B, C),
                 "%.17g*cos(%g*x)*sin(%g*y)*cos(%g*z)" % ((LAM + MU) * A * B, A, B, C),
                 "%.17g*cos(%g*x)*cos(%g*y)*sin(%g*z)" % ((LAM + MU) * A * C, A, B, C)]
    return exact, force


def case_yaml(dim, order):
    exact, force = fields(dim)
    faces = ["left", "right", "bottom", "top"] + (["front", "back"] if dim == 3 else [])
    q = lambda v: "[" + ", ".join("'%s'" % e for e in v) + "]"  # noqa: E731
    lines = ["dimension: %d" % dim,
             "mesh: {geo: body.geo, order: %d}" % order,
             "materials: {m: {model: linear_elastic, young: %g, poisson: %g}}" % (E, NU),
             "bodies: [{region: body, material: m}]",
             "boundary_conditions:"]
    lines += ["  - {region: %s, type: dirichlet, value: %s}" % (f, q(exact)) for f in faces]
    lines += ["  - {region: body, type: body_force, value: %s}" % q(force),
              "time: {integrator: static, end: 1, steps: 1}",
              "output: {exact_displacement: %s}" % q(exact)]
    return "\n".join(lines) + "\n"


def study(dim, kind, order, sizes, expect_l2, expect_h1, np=1):
    hs, l2, h1 = [], [], []
    for h in sizes:
        work = tempfile.mkdtemp(prefix="seam_conv_")
        geo = geometry.rectangle(kind, h, order) if dim == 2 else geometry.box(kind, h, order)
        H.write_case(work, "body.geo", geo)
        yaml = H.write_case(work, "case.yaml", case_yaml(dim, order))
        out = H.solve(yaml, np=np)
        err = H.read_csv(os.path.join(out, "errors.csv"))[-1]
        hs.append(h)
        l2.append(err["l2_error"])
        h1.append(err["h1_error"])
        H.cleanup(out, work)
    s_l2, s_h1 = H.slope(hs, l2), H.slope(hs, h1)
    print("%dD %s order %d: h = %s" % (dim, kind, order, hs))
    print("   L2 = %s  slope %.3f" % (" ".join("%.3e" % e for e in l2), s_l2))
    print("   H1 = %s  slope %.3f" % (" ".join("%.3e" % e for e in h1), s_h1))
    if abs(s_l2 - expect_l2) > 0.15 or abs(s_h1 - expect_h1) > 0.15:
        raise AssertionError("slopes L2 %.3f (expected %g), H1 %.3f (expected %g)"
                             % (s_l2, expect_l2, s_h1, expect_h1))


def test_2d_quad4(): study(2, "quad_structured", 1, [0.25, 0.125, 0.0625, 0.03125], 2, 1)
def test_2d_tri3(): study(2, "tri", 1, [0.2, 0.1, 0.05, 0.025], 2, 1)
def test_2d_quad9(): study(2, "quad_structured", 2, [0.5, 0.25, 0.125, 0.0625], 3, 2)
def test_2d_tri6_np3(): study(2, "tri", 2, [0.4, 0.2, 0.1, 0.05], 3, 2, np=3)
def test_3d_hex8(): study(3, "hex_structured", 1, [0.5, 0.25, 0.125, 0.0625], 2, 1)
def test_3d_hex27(): study(3, "hex_structured", 2, [1.0, 0.5, 0.25, 0.125], 3, 2)


if __name__ == "__main__":
    H.main([test_2d_quad4, test_2d_tri3, test_2d_quad9, test_2d_tri6_np3, test_3d_hex8,
            test_3d_hex27])
