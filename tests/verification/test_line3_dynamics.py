"""Energy-momentum contact of line3 faces (issue 13; docs/contact_dynamics.md §5): two free
rings of quadratic cells colliding (test_line3_free_rings), a ring of quadratic cells thrown
onto rigid obstacles (test_line3_ring_on_obstacles) and the bar impact with quadratic cells
(test_line3_bar_impact).

The ring of test_rings.py meshed with quadratic quadrilaterals (quad9 cells, line3 boundary
faces; 6 cells per quarter circle, 2 through the wall) thrown obliquely and spinning onto a
rigid plane (standard multipliers) and a rigid circle of radius 6 (dual multipliers), 2D,
`integrator: energy_momentum`, Newton tolerance 1e-12. The weighted gaps of the curved line3
facets against the obstacle (the whole-facet kernel on Hyper<6>) take the discrete-gradient
force, so no step gains energy (1e-8 of E_0 asserted; the measured rises are round-off), the
energy is constant to that in persistent contact, the momentum along the plane and the
angular momentum about the circle's centre are kept to 1e-12 (check_ring_on_obstacle of
test_rings.py). With the force of the end of the step
(the build before this one) the same cases gained up to 2.8e-4 (plane) and 2.4e-5 (circle)
of the energy in a step.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness as H  # noqa: E402
import test_rings as R  # noqa: E402
import test_self_contact as S  # noqa: E402


def line3_ring_on_obstacle(obstacle, multiplier="dual", np=1, n=6, steps=60):
    """ring_on_obstacle of test_rings.py on a second-order mesh (quad9 cells, line3 faces)."""
    yaml = (R.OBSTACLE_YAML.replace("DIM", "2")
            .replace("VELOCITY", R.OBSTACLE_VELOCITY[2])
            .replace("MULTIPLIER", "multiplier: %s," % multiplier)
            .replace("OBSTACLE", R.OBSTACLES[obstacle][2]).replace("STEPS", str(steps))
            .replace("END", "0.3"))
    rows, itf, newton = R.run_rings(2, ((0.0, 1.05),), n, yaml, np, order=2)
    return R.obstacle_energy(rows, itf, newton, "line3 ring on a rigid %s, %s multipliers, np %d"
                             % (obstacle, multiplier, np))


def test_line3_ring_on_obstacles():
    """check_ring_on_obstacle (test_rings.py) for the quadratic ring on the plane (standard)
    and on the circle (dual). (np 3 = np 1 on the circle measured: 3.4e-14 of the energy,
    2.0e-12 of the contact force; the free rings assert it.)"""
    R.check_ring_on_obstacle(line3_ring_on_obstacle("plane", multiplier="standard"), 2, "plane")
    R.check_ring_on_obstacle(line3_ring_on_obstacle("sphere"), 2, "sphere")
    print("   for comparison, the force of the end of the step (the build before, measured): "
          "largest energy rise in a step 2.8e-4 (plane), 2.4e-5 (circle)")


def test_line3_free_rings():
    """The two free rings of test_rings.py (8 cells per quarter circle, 2 through the wall) with
    quadratic cells (quad9, line3 faces), one `surface:` interface, energy_momentum, 40 steps:
    the line3 weighted gaps between the bodies (gap_blocks.cpp, Hyper<20>) take the discrete
    gradient. Linear and angular momentum through the impact to 1e-12 of their scales, no step
    gains more than 1e-10 of the energy and it is constant to that in persistent contact
    (check_free and check_energy_momentum of test_rings.py); np 3 equals np 1. With the force
    of the end of the step (the build before) the angular momentum drifted by 1.2e-2 and a step
    gained 1.1e-1 of the energy (1.37 of the start after 40 steps)."""
    r1 = R.free_bodies(2, "energy_momentum", n=8, order=2)
    R.check_free(r1, "energy_momentum")
    R.check_energy_momentum(r1, 2)
    r3 = R.free_bodies(2, "energy_momentum", n=8, order=2, np=3)
    R.check_free(r3, "energy_momentum")
    R.check_energy_momentum(r3, 2)
    R.check_np3_equals_np1(r3, r1)
    print("   for comparison, the force of the end of the step (the build before, measured): "
          "angular momentum 1.2e-2, largest energy rise in a step 1.1e-1")


def test_line3_bar_impact():
    """The bar impact of test_self_contact.py with quadratic cells (20 x 2 quad9 per bar, line3
    end faces), two bodies, energy_momentum: check_bar (contact 2 L / c within two steps, the
    stress rho c v / 2 to 2 %, the velocities exchanged, momentum to 1e-10, no step gaining
    more than 1e-12 of the energy). Measured: duration 2.025, stress 0.0050023, largest rise
    1.8e-14. (The end-of-step force also conserves here: 2.4e-14; matching flat faces.)"""
    r = S.bar_impact(S.BAR_TWO_BODY, "energy_momentum", nx=20, gap=0.01015, order=2)
    S.check_bar(r, "energy_momentum")


if __name__ == "__main__":
    H.main([test_line3_ring_on_obstacles, test_line3_free_rings, test_line3_bar_impact])
