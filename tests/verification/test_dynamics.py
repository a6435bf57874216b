"""Nonlinear elastodynamics across mortar interfaces (issue: elastodynamics).

1. Free flight of two tied Neo-Hookean bodies with non-matching meshes, given a rigid rotation
   plus a translation plus a stretching mode: with the energy-momentum method the total
   energy, the linear momentum and the angular momentum stay constant to 1e-10 (relative)
   while the bodies deform; 2D and 3D, condensed and saddle point, np = 1 and 3.
2. Generalized-alpha (rho_inf = 0.8) on a vibrating tied pair: the energy never grows and
   decays overall.
3. Newton at the round-off floor: the same free flight with the Newton tolerance at 1e-14 and
   1e-16, below what round-off allows once the displacements have grown, converges every step
   without a step cut (the step is accepted with a warning that states the attained residual)
   and conserves energy and momenta as before.
4. Order of accuracy in time: a bar vibrating in its first mode; the differences of the probe
   displacement between runs with dt, dt/2, dt/4 shrink by 4 (second order) for both schemes.
"""
import math
import os
import re
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import geometry  # noqa: E402
import harness as H  # noqa: E402


def flight_yaml(dim, integrator, strategy, steps, end, tol=1e-12):
    if dim == 2:
        v = ["-3*(y-1) + 1 + 0.5*(x-0.5)", "3*(x-0.5) + 0.5"]
    else:
        v = ["-3*(y-0.5) + 1 + 0.5*(x-0.5)", "3*(x-0.5) + 0.5 + 1*(z-1)", "-1*(y-0.5) + 0.2"]
    q = "[" + ", ".join("'%s'" % e for e in v) + "]"
    return "\n".join([
        "dimension: %d" % dim,
        "mesh: {geo: body.geo}",
        "materials: {m: {model: neo_hooke, young: 100, poisson: 0.3, density: 1}}",
        "bodies: [{region: lower, material: m}, {region: upper, material: m}]",
        "initial_conditions:",
        "  - {region: lower, velocity: %s}" % q,
        "  - {region: upper, velocity: %s}" % q,
        "interfaces:",
        "  - {name: tie, type: mesh_tying, slave: upper_bottom, master: lower_top, strategy: %s}" % strategy,
        "time: {integrator: %s, end: %g, steps: %d}" % (integrator, end, steps),
        "solver: {newton: {tolerance: %g}}" % tol,
        "output: {every: 1000}",
    ]) + "\n"


def run(geo, yaml_text, np=1):
    work = tempfile.mkdtemp(prefix="seam_dyn_")
    H.write_case(work, "body.geo", geo)
    yaml = H.write_case(work, "case.yaml", yaml_text)
    out = H.solve(yaml, np=np)
    rows = H.read_csv(os.path.join(out, "steps.csv"))
    H.cleanup(work, out)
    return rows


def drift(values):
    scale = max(abs(v) for v in values)
    return (max(values) - min(values)) / scale if scale > 0 else 0.0


def check_conservation(rows, dim, tol=1e-10):
    energy = [r["total_energy"] for r in rows]
    comps = ["momentum_x", "momentum_y"] + (["momentum_z"] if dim == 3 else [])
    angular = ["angular_momentum_z"] if dim == 2 else ["angular_momentum_x", "angular_momentum_y",
                                                        "angular_momentum_z"]
    strain = max(r["internal_energy"] for r in rows)
    if strain < 1e-3 * energy[0]:
        raise AssertionError("the bodies hardly deform (strain energy %.3e)" % strain)
    report = {"energy": drift(energy)}
    for c in comps + angular:
        report[c] = drift([r[c] for r in rows])
    print("   drifts over %d steps: %s" % (len(rows), ", ".join("%s %.2e" % kv for kv in report.items())))
    for k, d in report.items():
        if d > tol:
            raise AssertionError("%s drifts by %.3e (> %g)" % (k, d, tol))


def test_emm_2d_condensed():
    rows = run(geometry.tied_rectangles(0.3, 0.2), flight_yaml(2, "energy_momentum", "condensed", 100, 1.0))
    check_conservation(rows, 2)


def test_emm_2d_saddle_point_np3():
    rows = run(geometry.tied_rectangles(0.3, 0.2), flight_yaml(2, "energy_momentum", "saddle_point", 60, 0.6), np=3)
    check_conservation(rows, 2)


def test_emm_3d_condensed_np3():
    rows = run(geometry.tied_boxes(0.6, 0.45), flight_yaml(3, "energy_momentum", "condensed", 40, 0.4), np=3)
    check_conservation(rows, 3)


def roundoff_flight(tol, steps=100, end=1.0):
    """The 2D free flight with Newton tolerance `tol`, not quiet: (steps.csv, stdout, stderr)."""
    work = tempfile.mkdtemp(prefix="seam_roundoff_")
    H.write_case(work, "body.geo", geometry.tied_rectangles(0.3, 0.2))
    yaml = H.write_case(work, "case.yaml",
                        flight_yaml(2, "energy_momentum", "condensed", steps, end, tol))
    out = os.path.join(work, "out")
    code, stdout, stderr = H.run(["run", yaml, "-o", out], check=False)
    rows = H.read_csv(os.path.join(out, "steps.csv")) if os.path.exists(
        os.path.join(out, "steps.csv")) else []
    H.cleanup(work)
    if code != 0:
        raise AssertionError("tolerance %g: exit code %d after %d of %d steps\n%s"
                             % (tol, code, len(rows), steps, (stdout + stderr)[-3000:]))
    return rows, stdout, stderr


def check_roundoff_run(tol, rows, stdout, stderr, steps=100, end=1.0):
    if "cutting the step" in stdout + stderr:
        raise AssertionError("tolerance %g: a step was cut" % tol)
    times = [r["time"] for r in rows]
    expected = [end * (k + 1) / steps for k in range(steps)]
    if len(times) != steps or max(abs(a - b) for a, b in zip(times, expected)) > 1e-12:
        raise AssertionError("tolerance %g: %d steps at other times than k dt" % (tol, len(times)))
    # Each warning names its step and the relative residual it reached; that residual is the
    # one steps.csv records for the step, and it lies above the tolerance (else no warning).
    warned = re.findall(r"seam: warning: step (\d+) at t = \S+: .*?relative residual "
                        r"([0-9.e+-]+)", stderr)
    by_step = {int(r["step"]): r["residual"] for r in rows}
    for step, residual in warned:
        attained = by_step[int(step)]
        H.assert_close(float(residual), attained, rtol=1e-3,
                       what="tolerance %g, step %s: warned residual vs steps.csv" % (tol, step))
        if attained <= tol:
            raise AssertionError("step %s warned although its residual %.3e meets %g"
                                 % (step, attained, tol))
    above = sum(1 for r in rows if r["residual"] > tol)
    if above != len(warned):
        raise AssertionError("tolerance %g: %d steps above the tolerance but %d warnings"
                             % (tol, above, len(warned)))
    print("   tolerance %g: %d steps, %d accepted at the round-off floor, largest residual %.2e, "
          "iterations %d..%d" % (tol, len(rows), len(warned), max(r["residual"] for r in rows),
                                 min(r["newton_iterations"] for r in rows),
                                 max(r["newton_iterations"] for r in rows)))
    return len(warned)


def test_roundoff_floor_1e14():
    rows, stdout, stderr = roundoff_flight(1e-14)
    check_roundoff_run(1e-14, rows, stdout, stderr)
    check_conservation(rows, 2, tol=1e-12)


def test_roundoff_floor_1e16():
    rows, stdout, stderr = roundoff_flight(1e-16)
    if check_roundoff_run(1e-16, rows, stdout, stderr) == 0:
        raise AssertionError("no step reported the round-off floor at tolerance 1e-16")
    check_conservation(rows, 2, tol=1e-12)


def test_generalized_alpha_dissipates():
    yaml = flight_yaml(2, "generalized_alpha", "condensed", 100, 1.0).replace(
        "-3*(y-1) + 1 + 0.5*(x-0.5)", "2*(x-0.5)").replace("3*(x-0.5) + 0.5", "-1*(y-1)")
    rows = run(geometry.tied_rectangles(0.3, 0.2), yaml)
    # The energy of the step states oscillates (generalized-alpha conserves an algorithmic
    # energy with alpha-weighted terms, not this one), but it must not grow over the run.
    energy = [r["total_energy"] for r in rows]
    e0 = energy[0]
    first, last = energy[:25], energy[-25:]
    print("   generalized-alpha: energy %.6e -> %.6e, max %.6e, mean of first/last 25 steps "
          "%.6e / %.6e" % (e0, energy[-1], max(energy), sum(first) / 25, sum(last) / 25))
    if max(energy) > 1.001 * e0:
        raise AssertionError("energy grows above its initial value: %s" % max(energy))
    if sum(last) / 25 >= sum(first) / 25:
        raise AssertionError("no numerical dissipation")


def bar_probe(integrator, steps):
    """A bar [0,4] x [0,1], fixed at x = 0, plane stress, nu = 0, started in its first mode."""
    yaml = "\n".join([
        "dimension: 2",
        "plane: stress",
        "mesh: {geo: body.geo}",
        "materials: {m: {model: linear_elastic, young: 100, poisson: 0.0, density: 1}}",
        "bodies: [{region: body, material: m}]",
        "boundary_conditions:",
        "  - {region: left, type: dirichlet, value: [0, 0]}",
        "initial_conditions:",
        "  - {region: body, velocity: ['sin(_pi*x/8)', '0']}",
        "time: {integrator: %s, rho_inf: 1.0, end: 1.0, steps: %d}" % (integrator, steps)
        if integrator == "generalized_alpha" else
        "time: {integrator: %s, end: 1.0, steps: %d}" % (integrator, steps),
        "solver: {newton: {tolerance: 1.0e-12}}",
        "output: {every: 100000, probes: [[4, 0.5]]}",
    ]) + "\n"
    work = tempfile.mkdtemp(prefix="seam_bar_")
    H.write_case(work, "body.geo", geometry.rectangle("quad_structured", 0.5, 1, lx=4.0, ly=1.0))
    path = H.write_case(work, "case.yaml", yaml)
    out = H.solve(path)
    ux = H.read_csv(os.path.join(out, "probes.csv"))[-1]["ux"]
    H.cleanup(work, out)
    return ux


def order_study(integrator):
    u = [bar_probe(integrator, n) for n in (10, 20, 40, 80)]
    diffs = [abs(a - b) for a, b in zip(u, u[1:])]
    rates = [math.log2(a / b) for a, b in zip(diffs, diffs[1:])]
    # The continuum answer for comparison: u(L, 1) = sin(omega) / omega, omega = pi/8 sqrt(E/rho).
    omega = math.pi / 8 * math.sqrt(100.0)
    print("   %s: u(4, 1) = %s (continuum %.6f); observed orders %s"
          % (integrator, ["%.8f" % x for x in u], math.sin(omega) / omega,
             ["%.2f" % r for r in rates]))
    if min(rates) < 1.8:
        raise AssertionError("not second order in time: %s" % rates)


def test_order_energy_momentum(): order_study("energy_momentum")
def test_order_generalized_alpha(): order_study("generalized_alpha")


if __name__ == "__main__":
    H.main([test_emm_2d_condensed, test_emm_2d_saddle_point_np3, test_emm_3d_condensed_np3,
            test_roundoff_floor_1e14, test_roundoff_floor_1e16,
            test_generalized_alpha_dissipates, test_order_energy_momentum,
            test_order_generalized_alpha])
