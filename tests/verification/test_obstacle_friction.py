"""Coulomb friction against rigid obstacles with energy-momentum contact (issue 13;
docs/contact_dynamics.md §5, "Friction").

Friction (mu = 0.3, the same throw; 2D ring onto a plane and a circle, 3D onto the cylinder):
the normal part by the discrete gradient, the tangential part work conjugate to the slip
u~_j = sum_k D_jk dx_k over the step's mean D, so kinetic + strain energy E plus the
dissipation D that interfaces.csv reports (`frictional_dissipation`) never rises by more than
the Newton tolerance (1e-8 of E_0 asserted, ~1e-11 measured) and is constant to it in
persistent contact, D never decreases, and np = 3 equals np = 1. With the force of the end of
the step E + D rose by 6.0e-5 (plane, standard), 4.1e-5 (circle) and 2.6e-4 (cylinder).
"""
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness as H  # noqa: E402
import test_friction_dynamics as F  # noqa: E402
import test_rings as R  # noqa: E402
from test_obstacle_dynamics import CYLINDER  # noqa: E402


def friction_yaml(dimension, obstacle, multiplier, steps, mu):
    R.OBSTACLES.setdefault("cylinder", {3: CYLINDER})
    return (R.OBSTACLE_YAML.replace("DIM", str(dimension))
            .replace("VELOCITY", R.OBSTACLE_VELOCITY[dimension])
            .replace("MULTIPLIER", "multiplier: %s, friction: {model: coulomb, coefficient: %r},"
                     % (multiplier, mu))
            .replace("OBSTACLE", R.OBSTACLES[obstacle][dimension])
            .replace("STEPS", str(steps)).replace("END", "0.3"))


def ring_with_friction(dimension, obstacle, multiplier="dual", np=1, n=8, steps=60, mu=0.3):
    """The ring of test_rings.py (2D: 8 cells per quarter circle; 3D: extruded, n = 6) thrown
    obliquely and spinning onto a rigid plane (or the cylinder) with Coulomb friction, mu =
    0.3, energy_momentum to t = 0.3. Returns E = kinetic + strain energy and D =
    frictional_dissipation of interfaces.csv per step, the slip and active node counts."""
    yaml = friction_yaml(dimension, obstacle, multiplier, steps, mu)
    rows, itf, newton = R.run_rings(dimension, ((0.0, 1.05),), n, yaml, np)
    e = [r["total_energy"] for r in rows]
    d = [r["frictional_dissipation"] for r in itf]
    if len(d) != len(e):
        raise AssertionError("%d rows of interfaces.csv for %d steps" % (len(d), len(e)))
    total = [a + b for a, b in zip(e, d)]
    rise = max(b - a for a, b in zip(total, total[1:])) / e[0]
    persistent = R.persistent_steps(rows, newton)
    change = max([abs(total[k] - total[k - 1]) / e[0] for k in persistent] or [0.0])
    increment = min(b - a for a, b in zip(d, d[1:])) / e[0]
    slip = sum(r["slip_nodes"] for r in itf)
    stick = sum(r["active_nodes"] - r["slip_nodes"] for r in itf)
    print("   %dD ring on a rigid %s, mu = %g, %s multipliers, np %d: %d persistent steps, %d "
          "stick and %d slip node-steps; D = %.3e of E_0; largest rise of E + D in a step "
          "%.2e, largest change in persistent contact %.2e; smallest dissipation increment "
          "%.1e; E + D end/start %.8f"
          % (dimension, obstacle, mu, multiplier, np, len(persistent), stick, slip,
             d[-1] / e[0], rise, change, increment, total[-1] / e[0]))
    return dict(rows=rows, energy=e, dissipation=d, rise=rise, change=change,
                increment=increment, slip=slip, stick=stick, persistent=persistent,
                force=[r["normal_force"] for r in itf])


def check_friction(r):
    """E + D never rises beyond the Newton tolerance (1e-8 of E_0; measured ~1e-12) and is
    constant to it in persistent contact, where the energy lost is the dissipation that
    interfaces.csv reports; D never decreases (1e-12 of E_0); the friction did work (some
    nodes slipped, D > 1e-4 E_0)."""
    if len(r["persistent"]) < 3:
        raise AssertionError("only %d steps of persistent contact" % len(r["persistent"]))
    if r["slip"] == 0 or r["dissipation"][-1] < 1e-4 * r["energy"][0]:
        raise AssertionError("the friction did no work (%d slip node-steps, D = %.3e)"
                             % (r["slip"], r["dissipation"][-1]))
    if r["rise"] > 1e-8 or r["change"] > 1e-8:
        raise AssertionError("E + D rose by %.3e in a step; changed by %.3e in persistent contact"
                             % (r["rise"], r["change"]))
    if r["increment"] < -1e-12:
        raise AssertionError("the dissipation fell by %.3e in a step" % -r["increment"])


def test_friction_on_obstacles():
    """A ring thrown obliquely and spinning onto a rigid plane with mu = 0.3 (2D; standard
    multipliers at np 1 and 3), onto a rigid circle (2D, R = 6, dual) and the
    extruded ring onto the rigid cylinder (3D, dual): check_friction; np 3 equals np 1
    (contact force, energy, dissipation)."""
    r1 = ring_with_friction(2, "plane", multiplier="standard")
    check_friction(r1)
    r3 = ring_with_friction(2, "plane", multiplier="standard", np=3)
    check_friction(r3)
    R.check_np3_equals_np1(r3, r1)
    dd = max(abs(a - b) for a, b in zip(r1["dissipation"], r3["dissipation"])) / r1["energy"][0]
    print("   np 3 vs np 1: dissipation %.2e of E_0" % dd)
    if dd > 1e-10:
        raise AssertionError("np 3 dissipation differs from np 1 by %.3e" % dd)
    check_friction(ring_with_friction(2, "sphere"))
    check_friction(ring_with_friction(3, "cylinder", n=6, steps=40))
    print("   for comparison, the force of the end of the step (the build before, measured): "
          "largest rise of E + D in a step 6.0e-5 (plane, standard), 4.1e-5 (circle), 2.6e-4 "
          "(cylinder)")


def test_restart_friction_on_plane_np3():
    """The ring on the plane (standard multipliers, mu = 0.3) with a checkpoint every 5 steps,
    continued from the checkpoint of step 30 (sliding on the plane) on 3 ranks: the step's mean
    D needs the last converged step's D (the checkpoint's friction history). Energy and
    dissipation of the continued steps equal the uninterrupted run's to 1e-10 of E_0."""
    yaml = friction_yaml(2, "plane", "standard", 60, 0.3).replace(
        "output: {every: 1000}", "output: {every: 1000, checkpoint_every: 5}")
    work = tempfile.mkdtemp(prefix="seam_obstacle_friction_restart_")
    H.write_case(work, "case.geo", R.ring_geo(((0.0, 1.05),), 8, 2))
    path = H.write_case(work, "case.yaml", yaml)
    b, bi, de, dd = F.continued_on_3_ranks(work, path, "checkpoint_00030")
    slipping = sum(bi[k]["slip_nodes"] > 0 for k in bi)
    print("   restart from step 30 on 3 ranks: %d steps (%d with slip), energy %.2e, "
          "dissipation %.2e" % (len(b), slipping, de, dd))
    if len(b) != 30 or slipping == 0 or de > 1e-10 or dd > 1e-10:
        raise AssertionError("restart: %d steps, %d with slip, energy %.3e, dissipation %.3e"
                             % (len(b), slipping, de, dd))


if __name__ == "__main__":
    H.main([test_friction_on_obstacles, test_restart_friction_on_plane_np3])
