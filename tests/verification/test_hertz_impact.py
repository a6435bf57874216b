"""Hertz impact: an elastic sphere dropped on a rigid plane (implicit dynamics, 3D contact).

The sphere (R = 1, E = 1000, nu = 0.3, rho = 1, linear elastic) touches the plane z = 0 at
t = 0 with the velocity v, is stopped and thrown back. A quarter model (symmetry planes x = 0
and y = 0) of tetrahedra graded towards the contact point; the plane's force is a quarter of
the sphere's. Hertz's impact theory (Johnson 1985, Sect. 11.4) for a sphere on a rigid plane
(m* = m, R* = R, 1/E* = (1 - nu^2) / E) treats the contact as the quasi-static Hertz spring
F = 4/3 E* sqrt(R) delta^(3/2) between the plane and a rigid mass. Energy conservation,
m v^2 / 2 = 8/15 E* sqrt(R) delta^(5/2), gives the largest approach and force,
    delta_max = (15 m v^2 / (16 E* sqrt(R)))^(2/5),  F_max = 4/3 E* sqrt(R) delta_max^(3/2),
and integrating m d(delta)/dt = sqrt(m v^2 - 16/15 E* sqrt(R) delta^(5/2)) over the approach
and the rebound the contact duration
    t_c = 2 (delta_max / v) int_0^1 dx / sqrt(1 - x^(5/2)) = 2.9432 delta_max / v
        = 2.87 (m^2 / (R E*^2 v))^(1/5).
The integral is evaluated here (Gauss-Chebyshev after x = 1 - s^2) and checked against 2.87.
m is the mass of the meshed sphere, from its initial momentum (the faceted sphere is lighter
than 4/3 pi R^3 by the chordal error).

The theory holds when the impact is slow against the waves (t_c is 14 transit times 2 R / c_p
here, v / c_p = 2.6e-4) and the contact small (a / R = sqrt(delta_max / R)). The sphere's own
compliance beyond the contact zone is not in Hertz's spring, and the departure falls with
delta_max / R as its square root: at delta_max / R = 0.01 (a / R = 0.1; references of the
exact sphere's mass) the peak force came out +5.0 % (822 nodes), +4.9 % (2191 nodes), +4.4 %
(tet10), +5.4 % (dt / 2) above Hertz and the duration 3.5 to 5.1 % short; at
delta_max / R = 0.0025 +2.8 % and -2.3 % (2926 nodes). So the cases run at
delta_max / R = 0.0025 (a / R = 0.05) with the contact radius resolved by 8 to 12 elements: CI
on 1085 nodes, SEAM_FULL=1 on 2926 nodes and the CI mesh on 3 ranks against 1.

Measured: the contact duration from the first step (touching at t = 0) to the zero of the
force, extrapolated from the last two steps with force by F^(2/3) linear in time (Hertz:
F ~ delta^(3/2), delta linear in t at the end); the peak force from a parabola through the
largest step value and its neighbours. Measured (generalized-alpha, rho_inf = 0.8): 1085
nodes -2.66 % and +3.86 % (-2.70 % and +4.07 % before the persistency of the contact
velocities, docs/contact_dynamics.md §6), 2926 nodes -2.01 % and +3.32 % (before it); np 3
equal to np 1. The energy bound of generalized-alpha at impacts (§6) leaves both figures of the
CI mesh as they were to 5e-5 of them (-2.67 %, +3.86 %; 2926 nodes: -2.01 %, +3.24 %) and
its largest gain in a step at 1.5e-16 of the energy (4.72e-3 without it: the restarts from
the acceleration of equilibrium while the contact shrinks and after the release ring in the
stiff modes of the graded mesh).
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness as H  # noqa: E402
import test_contact as T  # noqa: E402

E, NU, RHO, R = 1000.0, 0.3, 1.0, 1.0

# A quarter sphere whose pole touches z = 0; the element size grows from H0 at the pole by K
# per unit distance up to HMAX.
GEO = """SetFactory("OpenCASCADE");
R = 1.0; h0 = H0; k = K; hmax = HMAX;
Sphere(1) = {0, 0, R, R, -Pi/2, Pi/2, Pi/2};
Field[1] = MathEval;
Field[1].F = Sprintf("%g + %g * sqrt(x * x + y * y + z * z)", h0, k);
Background Field = 1;
Mesh.MeshSizeMax = hmax;
Mesh.MeshSizeExtendFromBoundary = 0; Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;
eps = 1e-6;
b() = Boundary{ Volume{1}; };
sx() = Surface In BoundingBox{-eps, -eps, -eps, eps, R + eps, 2 * R + eps};
sy() = Surface In BoundingBox{-eps, -eps, -eps, R + eps, eps, 2 * R + eps};
skin() = b(); skin() -= sx(); skin() -= sy();
Physical Volume("ball") = {1};
Physical Surface("sym_x") = sx();
Physical Surface("sym_y") = sy();
Physical Surface("skin") = skin();
"""

YAML = """dimension: 3
mesh: {geo: case.geo}
materials:
  m: {model: linear_elastic, young: %r, poisson: %r, density: %r}
bodies:
  - {region: ball, material: m}
boundary_conditions:
  - {region: sym_x, type: dirichlet, components: [x], value: [0]}
  - {region: sym_y, type: dirichlet, components: [y], value: [0]}
initial_conditions:
  - {region: ball, velocity: ["0", "0", "%r"]}
interfaces:
  - {name: contact, type: contact, slave: skin, rigid_plane: {point: [0, 0, 0], normal: [0, 0, 1]}}
time: {integrator: INTEGRATOR, end: %r, steps: %d}
solver: {newton: {tolerance: 1.0e-10, max_iterations: 30}}
output: {every: 100000}
"""


def duration_integral(n=200):
    """int_0^1 dx / sqrt(1 - x^(5/2)): with x = 1 - s^2 the integrand 2 s / sqrt(1 - x^(5/2))
    is smooth on [0, 1] (1 - x^(5/2) ~ 5/2 s^2), integrated by the midpoint rule."""
    total = 0.0
    for i in range(n):
        s = (i + 0.5) / n
        x = 1.0 - s * s
        total += 2.0 * s / math.sqrt(1.0 - x ** 2.5) / n
    return total


def hertz(m, v):
    e_star = E / (1.0 - NU * NU)
    d_max = (15.0 * m * v * v / (16.0 * e_star * math.sqrt(R))) ** 0.4
    f_max = 4.0 / 3.0 * e_star * math.sqrt(R) * d_max ** 1.5
    t_c = 2.0 * duration_integral() * d_max / v
    # Johnson's closed form, 2.87 (m^2 / (R E*^2 v))^(1/5), to its three digits.
    t_closed = 2.87 * (m * m / (R * e_star * e_star * v)) ** 0.2
    if abs(t_c / t_closed - 1.0) > 2e-3:
        raise AssertionError("Hertz duration %.6g differs from 2.87 (...)^(1/5) = %.6g"
                             % (t_c, t_closed))
    return d_max, f_max, t_c


_last = {}  # the rows of steps.csv of the last impact()


def impact(ratio, h0, k, hmax, steps_in_contact, integrator="generalized_alpha", np=1):
    """The sphere at the velocity that gives delta_max / R = ratio (for the exact sphere's mass)
    on a mesh (h0, k, hmax). Returns (t_c, F_max, references, mass)."""
    m_exact = RHO * 4.0 / 3.0 * math.pi * R ** 3
    e_star = E / (1.0 - NU * NU)
    # delta_max = ratio R  <=>  v^2 = 16 E* sqrt(R) (ratio R)^(5/2) / (15 m).
    v = math.sqrt(16.0 * e_star * math.sqrt(R) * (ratio * R) ** 2.5 / (15.0 * m_exact))
    t_ref = hertz(m_exact, v)[2]
    dt = t_ref / steps_in_contact
    steps = int(math.ceil(1.25 * t_ref / dt))
    geo = GEO.replace("H0", repr(h0)).replace("HMAX", repr(hmax)).replace("K;", repr(k) + ";")
    yaml = (YAML % (E, NU, RHO, -v, steps * dt, steps)).replace("INTEGRATOR", integrator)
    work, out = T.run_case(geo, yaml, np=np)
    itf = H.read_csv(os.path.join(out, "interfaces.csv"))
    rows = H.read_csv(os.path.join(out, "steps.csv"))
    _last["rows"] = rows
    H.cleanup(work, out)
    t = [0.0] + [r["time"] for r in itf]
    f = [0.0] + [4.0 * r["normal_force"] for r in itf]  # the whole sphere
    # Mass of the meshed quarter: its initial momentum, the first step's contact impulse
    # (trapezoidal) added back.
    m = 4.0 * (abs(rows[0]["momentum_z"]) + 0.5 * (t[1] - t[0]) * f[1] / 4.0) / v
    d_max, f_ref, t_c_ref = hertz(m, v)
    last = max(i for i in range(len(f)) if f[i] > 0.0)
    if last + 1 >= len(f):
        raise AssertionError("the sphere is still in contact at the end of the run")
    a, b = f[last - 1] ** (2.0 / 3.0), f[last] ** (2.0 / 3.0)
    if not a > b:
        raise AssertionError("the force does not fall at the end of the contact")
    t_c = t[last] + b / (a - b) * (t[last] - t[last - 1])
    i = max(range(1, last), key=lambda j: f[j])
    # Parabola through the largest value and its neighbours (equal steps).
    fm, f0, fp = f[i - 1], f[i], f[i + 1]
    curvature = fm - 2.0 * f0 + fp
    f_max = f0 - 0.125 * (fp - fm) ** 2 / curvature if curvature < 0.0 else f0
    c_p = math.sqrt(E * (1 - NU) / (RHO * (1 + NU) * (1 - 2 * NU)))
    print("   delta_max/R %.4g (a/R %.3f), v %.5g (v/c_p %.2e), t_c/(2R/c_p) %.1f, %s, %d steps:"
          " mass %.6f (sphere %.6f)" % (d_max / R, math.sqrt(d_max / R), v, v / c_p,
                                        t_c_ref * c_p / (2 * R), integrator, steps, m,
                                        m_exact))
    print("   contact duration %.5f (Hertz %.5f, %+.2f %%), peak force %.5f (Hertz %.5f, %+.2f %%)"
          % (t_c, t_c_ref, 100 * (t_c / t_c_ref - 1), f_max, f_ref, 100 * (f_max / f_ref - 1)))
    return t_c, f_max, t_c_ref, f_ref


def check(result, rtol):
    t_c, f_max, t_ref, f_ref = result
    H.assert_close(t_c, t_ref, rtol=rtol, what="contact duration against Hertz")
    H.assert_close(f_max, f_ref, rtol=rtol, what="peak force against Hertz")


def test_hertz_impact():
    """CI: delta_max / R = 0.0025 on 1085 nodes (h = 0.006 at the pole, 50 steps over t_c):
    duration and peak force within 5 % of Hertz; no step gains more than 1e-4 of the energy
    (issue 13) with generalized-alpha's energy bound at impacts, more without it
    (SEAM_KEEP_CONTACT_GAIN=1: the release step after the restart from the acceleration of
    equilibrium gained 4.7e-3), and the bound's first step keeps the momenta (all components:
    the supports' dofs keep their velocity) to 1e-12 of m v and m v R."""
    result = {}

    def run():
        result["impact"] = impact(0.0025, 0.006, 0.15, 0.25, 50)
        return _last["rows"]

    # the quarter model's momentum at t = 0 (before the first step's impulse): m v / 4
    scale = RHO * math.pi / 3.0 * 0.0093514
    _, _, rise, rise_kept, step, dp, dl = T.with_and_without_bound(run, scale, scale * R,
                                                                   ("xyz", "xyz"))
    print("   largest gain of a step: %.2e with the bound, %.2e without; first step of the "
          "bound %d: momentum change %.1e, angular %.1e" % (rise, rise_kept, step, dp, dl))
    check(result["impact"], 0.05)
    if rise > T.GA_IMPACT_GAIN:
        raise AssertionError("a step gained %.3e of the energy (> %.0e)" % (rise,
                                                                           T.GA_IMPACT_GAIN))
    if rise_kept < T.GA_IMPACT_GAIN:
        raise AssertionError("without the energy bound the largest gain is only %.3e: the "
                             "case does not show it" % rise_kept)
    if dp > 1e-12 or dl > 1e-12:
        raise AssertionError("the energy bound changed the momenta by %.3e, %.3e" % (dp, dl))


@H.full_only
def test_hertz_impact_fine():
    """2926 nodes (h = 0.004 at the pole, 70 steps over t_c), within 5 % of Hertz; the CI mesh
    on 3 ranks gives the duration and peak force of 1 rank to 1e-8."""
    check(impact(0.0025, 0.004, 0.1, 0.2, 70), 0.05)
    one = impact(0.0025, 0.006, 0.15, 0.25, 50)
    e1 = [r["total_energy"] for r in _last["rows"]]
    three = impact(0.0025, 0.006, 0.15, 0.25, 50, np=3)
    e3 = [r["total_energy"] for r in _last["rows"]]
    for a, b, what in zip(one, three, ("duration", "peak force", "", "")):
        if what:
            H.assert_close(b, a, rtol=1e-8, what="np 3 against np 1, " + what)
    worst = max(abs(a - b) for a, b in zip(e1, e3)) / e1[0]
    print("   np 3 vs np 1: energy %.1e" % worst)
    if worst > 1e-10 or len(e1) != len(e3):
        raise AssertionError("np 3 energies differ from np 1's by %.3e" % worst)


if __name__ == "__main__":
    H.main([test_hertz_impact, test_hertz_impact_fine])
