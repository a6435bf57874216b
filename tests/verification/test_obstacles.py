"""Rigid round obstacles (rigid_sphere, a circle in 2D, and rigid_cylinder) against analytic
solutions.

- 2D Hertz: a rigid circle (R = 1) pressed into an elastic block (plane strain, half model with
  a symmetry line). Johnson (Contact Mechanics, Sect. 4.3) for a load F per unit length gives
  the half-width b = sqrt(4 R F / (pi E*)), E* = E / (1 - nu^2), independently of the block's
  depth; seam's b is fitted to the active nodes' tractions (contact_analysis.fitted_hertz)
  and must agree with the b of the measured force (F = 2 x the half model's normal force)
  within 3 %. np = 3 gives the np = 1 force and active set.
- 3D Hertz: a rigid sphere (R = 1) indenting a block by d = 0.01 (quarter model with two
  symmetry planes, hex8 graded towards the contact). The half-space solution
  F = 4/3 E* sqrt(R) d^(3/2), a = sqrt(R d) holds for a block much larger than a; the block
  here (2 x 2 x 2, a = 0.1) has a clamped base, stiffer than the half-space by Boussinesq's
  displacement u_z(H) of the point at depth H under the load, which the test adds to d
  (first order) before comparing: force within 4 %, contact radius (fitted to the
  tractions) within 5 %. SEAM_FULL: a finer mesh on 3 ranks.
- A rigid cylinder with its axis along y pressing a block whose front and back faces are
  held in y (plane strain) and whose hexahedra are the extrusion of the 2D quadrilaterals:
  the force per unit length equals the 2D rigid-circle result on the same section to 1e-6
  (the dual basis of a rectangle quad4 is the tensor product of the line2 ones), np = 3.
- The iterative contact path (GMRES + GAMG with the preconditioner kept within a load step,
  the condensed matrix updated in place, the inexact Newton forcing term and the constant
  linear_elastic tangent): a step-42-like cube (10^3 hex8, 3,993 dofs) indented by a rigid
  sphere in two load steps, `linear: iterative` on 1 and 3 ranks, equals the direct (MUMPS)
  solve: the same Newton iterations per step and active nodes, forces and probe displacements
  within 1e-8. A negative control loosens the Krylov tolerance (-ksp_rtol 1e-3): the same
  comparison must then fail (more Newton iterations, forces off by about 3e-5).
- Bad input: negative radius, zero axis, rigid_plane together with rigid_sphere, a 2D
  rigid_cylinder, a cylinder key on a sphere: exit code 1 with a message at the line.
"""
import math
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import contact_analysis as C  # noqa: E402
import harness as H  # noqa: E402

E, NU = 1.0, 0.3
ESTAR = E / (1.0 - NU * NU)
_dirs = []


def run(geo, yaml, np=1):
    work = tempfile.mkdtemp(prefix="seam_obstacle_")
    _dirs.append(work)
    H.write_case(work, "case.geo", geo)
    path = H.write_case(work, "case.yaml", yaml)
    out = H.solve(path, np=np)
    _dirs.append(out)
    return out


def case_yaml(dimension, bcs, interface, steps=2):
    return "\n".join(
        ["dimension: %d" % dimension, "mesh: {geo: case.geo}",
         "materials:", "  m: {model: linear_elastic, young: %r, poisson: %r}" % (E, NU),
         "bodies:", "  - {region: body, material: m}", "boundary_conditions:"]
        + ["  - " + b for b in bcs]
        + ["interfaces:", "  - " + interface,
           "time: {integrator: static, end: 1, steps: %d}" % steps,
           "solver: {newton: {tolerance: 1.0e-10, max_iterations: 30}}"]) + "\n"


def interface_force(out):
    return H.last_step_rows(H.read_csv(os.path.join(out, "interfaces.csv")))[0]["normal_force"]


def slave_rows(out):
    return H.read_csv(os.path.join(out, "interface_contact.csv"))


# ---------------------------------------------------------------------------------------------
# 2D: rigid circle on a block (plane strain)


def block_2d_geo(h_fine, h_coarse=0.1, width=1.0, depth=1.0, fine=0.12):
    """[0, width] x [-depth, 0] triangles, h_fine on the top up to x = fine."""
    return "\n".join([
        "Point(1) = {0, 0, 0, %g};" % h_fine, "Point(2) = {%g, 0, 0, %g};" % (fine, h_fine),
        "Point(3) = {%g, 0, 0, %g};" % (width, h_coarse),
        "Point(4) = {%g, %g, 0, %g};" % (width, -depth, h_coarse),
        "Point(5) = {0, %g, 0, %g};" % (-depth, h_coarse),
        "Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5};",
        "Line(5) = {5, 1};", "Curve Loop(1) = {-5, -4, -3, -2, -1}; Plane Surface(1) = {1};",
        'Physical Curve("top") = {1, 2}; Physical Curve("right") = {3};',
        'Physical Curve("bottom") = {4}; Physical Curve("symmetry") = {5};',
        'Physical Surface("body") = {1};']) + "\n"


def circle_yaml(radius, depth_of_press):
    return case_yaml(2, ["{region: symmetry, type: dirichlet, components: [x], value: [0]}",
                         "{region: bottom, type: dirichlet, components: [x, y], value: [0, 0]}"],
                     "{name: contact, type: contact, slave: top, rigid_sphere: {center: [0, %r], "
                     "radius: %r, motion: ['0', '-%r*t']}}" % (radius, radius, depth_of_press))


def test_hertz_2d_circle():
    """Half-width against Johnson's b(F); np = 3 equals np = 1."""
    R = 1.0
    geo, yaml = block_2d_geo(0.004), circle_yaml(R, 0.005)
    out = run(geo, yaml)
    F = 2.0 * interface_force(out)
    b_ref, p0_ref = C.hertz_2d(F, R, ESTAR)
    rows = slave_rows(out)
    p0, b = C.fitted_hertz(rows, 2, current=False)
    active = sum(1 for r in rows if C.is_active(r))
    print("   F = %.6g per length, %d active nodes; b = %.5g (Johnson %.5g, %+.2f %%), "
          "p0 = %.5g (Johnson %.5g, %+.2f %%)" % (F, active, b, b_ref, 100 * (b / b_ref - 1),
                                                 p0, p0_ref, 100 * (p0 / p0_ref - 1)))
    H.assert_close(b, b_ref, rtol=0.03, what="contact half-width b")
    H.assert_close(p0, p0_ref, rtol=0.03, what="peak pressure p0")
    # No slave node inside the circle (beyond the solver tolerance).
    for r in rows:
        x, y = r["x"] + r["ux"], r["y"] + r["uy"]
        if math.hypot(x, y - (R - 0.005)) < R - 1e-6:
            raise AssertionError("slave node %d inside the circle" % r["node"])
    out3 = run(geo, yaml, np=3)
    H.assert_close(2.0 * interface_force(out3), F, rtol=1e-8, what="np = 3 force")
    active3 = sum(1 for r in slave_rows(out3) if C.is_active(r))
    if active3 != active:
        raise AssertionError("np = 3: %d active nodes, np = 1: %d" % (active3, active))


# ---------------------------------------------------------------------------------------------
# 3D: rigid sphere indenting a block (Hertz)


def block_3d_geo(n, progression, size=2.0):
    """Quarter block [0, size]^2 x [-size, 0] of n^3 hexahedra, every edge graded by
    `progression` towards the first contact point (0, 0, 0)."""
    return "\n".join([
        'SetFactory("OpenCASCADE");',
        "Box(1) = {0, 0, %g, %g, %g, %g};" % (-size, size, size, size),
        "For c In {1:12}",
        "  pts() = PointsOf{ Curve{c}; };",
        "  p0() = Point{pts(0)};",
        "  p1() = Point{pts(1)};",
        "  If (Fabs(p0(0)) + Fabs(p0(1)) + Fabs(p0(2)) < Fabs(p1(0)) + Fabs(p1(1)) + Fabs(p1(2)))",
        "    Transfinite Curve{c} = %d Using Progression %r;" % (n + 1, progression),
        "  Else",
        "    Transfinite Curve{c} = %d Using Progression %r;" % (n + 1, 1.0 / progression),
        "  EndIf",
        "EndFor",
        "Transfinite Surface{:}; Recombine Surface{:}; Transfinite Volume{1};",
        'Physical Surface("symmetry_x") = {1}; Physical Surface("right") = {2};',
        'Physical Surface("symmetry_y") = {3}; Physical Surface("back") = {4};',
        'Physical Surface("bottom") = {5}; Physical Surface("top") = {6};',
        'Physical Volume("body") = {1};']) + "\n"


def hertz_3d(n, progression, np=1):
    R, d, size = 1.0, 0.01, 2.0
    yaml = case_yaml(3, ["{region: symmetry_x, type: dirichlet, components: [x], value: [0]}",
                         "{region: symmetry_y, type: dirichlet, components: [y], value: [0]}",
                         "{region: bottom, type: dirichlet, components: [x, y, z], "
                         "value: [0, 0, 0]}"],
                     "{name: contact, type: contact, slave: top, rigid_sphere: {center: "
                     "[0, 0, %r], radius: %r, motion: ['0', '0', '-%r*t']}}" % (R, R, d))
    out = run(block_3d_geo(n, progression, size), yaml, np=np)
    F = 4.0 * interface_force(out)
    # Hertz's d is the approach of the sphere to points far inside the half-space. Under the
    # load F those points at depth H = size sink by Boussinesq's
    #   u_z(H) = F (1 + nu) (3 - 2 nu) / (2 pi E H)   (on the axis),
    # which the clamped base of the block does not: the half-space part is indented by d + u_z.
    d_eff = d + F * (1.0 + NU) * (3.0 - 2.0 * NU) / (2.0 * math.pi * E * size)
    F_ref = 4.0 / 3.0 * ESTAR * math.sqrt(R) * d_eff ** 1.5
    a_ref = math.sqrt(R * d_eff)
    rows = slave_rows(out)
    p0, a = C.fitted_hertz(rows, 3, current=False)
    print("   %d^3 hex8: F = %.6g (Hertz at d + u_z(H) = %.5g: %.6g, %+.2f %%; at d: %.6g), "
          "a = %.5g (sqrt(R d) %.5g, %+.2f %%), %d active nodes"
          % (n, F, d_eff, F_ref, 100 * (F / F_ref - 1), 4.0 / 3.0 * ESTAR * d ** 1.5, a, a_ref,
             100 * (a / a_ref - 1), sum(1 for r in rows if C.is_active(r))))
    H.assert_close(F, F_ref, rtol=0.04, what="Hertz force 4/3 E* sqrt(R) d^3/2")
    H.assert_close(a, a_ref, rtol=0.05, what="contact radius sqrt(R d)")
    return F


def test_hertz_3d_sphere():
    hertz_3d(16, 1.25)


@H.full_only
def test_hertz_3d_sphere_fine_np3():
    hertz_3d(24, 1.15, np=3)


# ---------------------------------------------------------------------------------------------
# The iterative contact path equals the direct solve


CUBE_GEO = "\n".join([
    'SetFactory("OpenCASCADE");', "Box(1) = {0, 0, 0, 1, 1, 1};", "Transfinite Curve{:} = 11;",
    "Transfinite Surface{:}; Recombine Surface{:}; Transfinite Volume{1};",
    'Physical Surface("sides") = {1, 2, 3, 4}; Physical Surface("bottom") = {5};',
    'Physical Surface("top") = {6}; Physical Volume("body") = {1};']) + "\n"


def sphere_on_cube(linear, np=1, extra=()):
    """The cube of deal.II's step-42 (E = 2e5, nu = 0.3, base clamped, sides on rollers) and
    its sphere (R = 0.6), pressed 0.01 and 0.02 into the top in two load steps: Newton
    iterations per step, forces and active nodes per step, probe displacements."""
    yaml = "\n".join([
        "dimension: 3", "mesh: {geo: case.geo}", "materials:",
        "  m: {model: linear_elastic, young: 2.0e5, poisson: 0.3}",
        "bodies:", "  - {region: body, material: m}", "boundary_conditions:",
        "  - {region: bottom, type: dirichlet, components: [x, y, z], value: [0, 0, 0]}",
        "  - {region: sides, type: dirichlet, components: [x, y], value: [0, 0]}",
        "interfaces:",
        "  - {name: indenter, type: contact, slave: top, rigid_sphere: {center: [0.5, 0.5, 1.6],"
        " radius: 0.6, motion: ['0', '0', '-0.02*t']}}",
        "time: {integrator: static, end: 1, steps: 2}",
        "solver: {newton: {tolerance: 1.0e-10, max_iterations: 30}, linear: %s}" % linear,
        "output: {probes: [[0.5, 0.5, 1.0], [0.7, 0.5, 1.0], [0.5, 0.5, 0.5]]}"]) + "\n"
    work = tempfile.mkdtemp(prefix="seam_obstacle_")
    _dirs.append(work)
    H.write_case(work, "case.geo", CUBE_GEO)
    out = H.solve(H.write_case(work, "case.yaml", yaml), np=np, extra=extra)
    _dirs.append(out)
    steps = H.read_csv(os.path.join(out, "steps.csv"))
    itf = H.read_csv(os.path.join(out, "interfaces.csv"))
    probes = H.read_csv(os.path.join(out, "probes.csv"))
    u = [r[k] for r in probes for k in ("ux", "uy", "uz")]
    return {"newton": [int(r["newton_iterations"]) for r in steps],
            "active": [int(r["active_nodes"]) for r in itf],
            "force": [r["normal_force"] for r in itf], "u": u}


def sphere_mismatch(run, ref):
    """What differs between two sphere_on_cube results beyond the test's tolerances ('' if
    nothing): Newton iterations and active nodes exactly, forces within 1e-8 relative, probe
    displacements within 1e-8 of the largest."""
    scale = max(abs(v) for v in ref["u"])
    problems = []
    for key in ("newton", "active"):
        if run[key] != ref[key]:
            problems.append("%s %s, direct %s" % (key, run[key], ref[key]))
    if any(abs(a - b) > 1e-8 * abs(b) for a, b in zip(run["force"], ref["force"])):
        problems.append("forces %s, direct %s" % (run["force"], ref["force"]))
    du = max(abs(a - b) for a, b in zip(run["u"], ref["u"]))
    if du > 1e-8 * scale:
        problems.append("probe displacements differ by %.3g of the largest" % (du / scale))
    return "; ".join(problems)


def test_sphere_iterative_equals_direct():
    direct = sphere_on_cube("direct")
    print("   direct: Newton %s, active %s, forces %s"
          % (direct["newton"], direct["active"], direct["force"]))
    for np in (1, 3):
        run = sphere_on_cube("iterative", np=np)
        problem = sphere_mismatch(run, direct)
        print("   iterative, np %d: Newton %s, forces %s %s"
              % (np, run["newton"], run["force"], problem or "(equal)"))
        if problem:
            raise AssertionError("iterative solve on %d rank(s) differs from the direct one: %s"
                                 % (np, problem))
    # The comparison can fail: a Krylov tolerance far above the Newton target is caught.
    loose = sphere_on_cube("iterative", extra=("--", "-ksp_rtol", "1e-3"))
    problem = sphere_mismatch(loose, direct)
    print("   iterative, -ksp_rtol 1e-3: %s" % (problem or "equal"))
    if not problem:
        raise AssertionError("a loosened Krylov tolerance (-ksp_rtol 1e-3) went unnoticed")


# ---------------------------------------------------------------------------------------------
# A cylinder along y on a block in plane strain equals the 2D circle per unit length


def section_geo(n_x, n_z, extrude=None):
    """[0, 1] x [-0.5, 0] structured quads (bias towards x = 0), or their extrusion by
    `extrude` = (length, layers) in y into hexahedra (then z is the section's second axis)."""
    lines = ["Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {1, -0.5, 0};",
             "Point(4) = {0, -0.5, 0};",
             "Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};",
             "Curve Loop(1) = {-4, -3, -2, -1}; Plane Surface(1) = {1};",
             "Transfinite Curve{1} = %d Using Progression 1.08;" % (n_x + 1),
             "Transfinite Curve{3} = %d Using Progression %r;" % (n_x + 1, 1 / 1.08),
             "Transfinite Curve{2, 4} = %d;" % (n_z + 1),
             "Transfinite Surface{1}; Recombine Surface{1};"]
    if extrude is None:
        lines += ['Physical Curve("top") = {1}; Physical Curve("bottom") = {3};',
                  'Physical Curve("symmetry") = {4}; Physical Surface("body") = {1};']
        return "\n".join(lines) + "\n"
    length, layers = extrude
    # The section lies in x-y; rotate it into x-z (y -> z) and extrude along y.
    lines += ["Rotate {{1, 0, 0}, {0, 0, 0}, Pi/2} { Surface{1}; }",
              "out[] = Extrude {0, %r, 0} { Surface{1}; Layers{%d}; Recombine; };"
              % (-length, layers),
              # Lateral faces in the order of the curve loop: x = 0, bottom, x = 1, top.
              'Physical Surface("top") = {out[5]}; Physical Surface("bottom") = {out[3]};',
              'Physical Surface("symmetry") = {out[2]};',
              'Physical Surface("faces") = {1, out[0]}; Physical Volume("body") = {out[1]};']
    return "\n".join(lines) + "\n"


def test_cylinder_line_contact_equals_2d():
    R, d, length = 1.0, 0.004, 0.3
    motion2 = "['0', '-%r*t']" % d
    yaml2 = case_yaml(2, ["{region: symmetry, type: dirichlet, components: [x], value: [0]}",
                          "{region: bottom, type: dirichlet, components: [x, y], value: [0, 0]}"],
                      "{name: contact, type: contact, slave: top, rigid_sphere: {center: [0, %r],"
                      " radius: %r, motion: %s}}" % (R, R, motion2))
    out2 = run(section_geo(30, 8), yaml2)
    yaml3 = case_yaml(3, ["{region: symmetry, type: dirichlet, components: [x], value: [0]}",
                          "{region: faces, type: dirichlet, components: [y], value: [0]}",
                          "{region: bottom, type: dirichlet, components: [x, y, z], "
                          "value: [0, 0, 0]}"],
                      "{name: contact, type: contact, slave: top, rigid_cylinder: {point: "
                      "[0, 0.7, %r], axis: [0, 1, 0], radius: %r, motion: ['0', '0', '-%r*t']}}"
                      % (R, R, d))
    out3 = run(section_geo(30, 8, extrude=(length, 2)), yaml3, np=3)
    f2, f3 = interface_force(out2), interface_force(out3) / length
    print("   force per unit length: 2D circle %.10g, 3D cylinder %.10g (rel. diff %.2e)"
          % (f2, f3, abs(f3 / f2 - 1)))
    if not f2 > 0:
        raise AssertionError("no contact force in 2D")
    H.assert_close(f3, f2, rtol=1e-6, what="cylinder force per length vs 2D")


# ---------------------------------------------------------------------------------------------
# Bad input


def test_bad_input():
    geo = block_2d_geo(0.1, fine=0.5)
    bcs = ["{region: bottom, type: dirichlet, components: [x, y], value: [0, 0]}"]
    cases = [
        (2, "rigid_sphere: {center: [0, 1], radius: -1}", "radius must be > 0"),
        (3, "rigid_cylinder: {point: [0, 0, 1], axis: [0, 0, 0], radius: 1}",
         "axis must not be the zero vector"),
        (2, "rigid_plane: {point: [0, 0], normal: [0, 1]}, rigid_sphere: {center: [0, 1], "
            "radius: 1}", "give only one of"),
        (2, "rigid_cylinder: {point: [0, 1], axis: [1, 0], radius: 1}", "needs dimension 3"),
        (2, "rigid_sphere: {center: [0, 1], axis: [1, 0], radius: 1}", "applies only to"),
    ]
    for dimension, obstacle, message in cases:
        work = tempfile.mkdtemp(prefix="seam_obstacle_bad_")
        _dirs.append(work)
        H.write_case(work, "case.geo", geo if dimension == 2 else
                     block_3d_geo(2, 1.0))
        yaml = case_yaml(dimension, bcs if dimension == 2 else
                         ["{region: bottom, type: dirichlet, components: [x, y, z], "
                          "value: [0, 0, 0]}"],
                         "{name: contact, type: contact, slave: top, %s}" % obstacle)
        path = H.write_case(work, "case.yaml", yaml)
        code, out, err = H.run(["check", path], check=False)
        text = out + err
        line = "case.yaml:%d" % (yaml.count("\n", 0, yaml.index("interfaces:")) + 2)
        print("   %s -> %d: %s" % (obstacle[:40], code, text.strip().splitlines()[-1][:110]))
        if code != 1 or message not in text or line not in text:
            raise AssertionError("expected exit 1 with '%s' at %s, got %d:\n%s"
                                 % (message, line, code, text))


TESTS = [test_hertz_2d_circle, test_hertz_3d_sphere, test_cylinder_line_contact_equals_2d,
         test_sphere_iterative_equals_direct, test_bad_input, test_hertz_3d_sphere_fine_np3]

if __name__ == "__main__":
    try:
        H.main(TESTS)
    finally:
        H.cleanup(*_dirs)
