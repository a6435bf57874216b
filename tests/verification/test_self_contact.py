"""Self and multi-body contact (`surface: [groups...]`): slave and master facets chosen at
every search.

- Two blocks pressed together (2D quads and 3D tetrahedra, non-matching meshes, nu = 0) as one
  `surface:` interface over both contact faces: every node of the face that the role rule made
  slave carries the pressure d / sum(H_i / E_i) to 1e-8 relative, the other face's nodes carry
  no multiplier, and the top reaction equals that of the same problem with the fixed
  slave/master interface (same slave face) to 1e-8 relative; np = 3 equals np = 1.
- A ring (2D annulus) squeezed between two rigid planes until its inner surface closes onto
  itself (one `surface:` interface over the inner circle): the deformed shape keeps the two
  mirror symmetries of the problem, no inner node penetrates the opposite side by more than
  1e-6 of the radius, the inner contact force is positive, the two plane forces balance to
  1e-8; np = 3 equals np = 1.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import contact_analysis as C  # noqa: E402
import geometry as G  # noqa: E402
import harness as H  # noqa: E402
import test_contact as T  # noqa: E402

E_LOWER, E_UPPER, D = 100.0, 40.0, 0.02
FACES = ("lower_top", "upper_bottom")


def blocks_yaml(dimension, interface, tilt):
    """The top pressed down by D (uniform), or by D (0.5 + x) (tilt: a non-uniform pressure,
    whose mortar discretization depends on which face is slave)."""
    top = "-%r*t*(0.5+x)" % D if tilt else "-%r*t" % D
    if dimension == 2:
        bcs = ["{region: bottom, type: dirichlet, components: [y], value: [0]}",
               "{region: left, type: dirichlet, components: [x], value: [0]}",
               "{region: top, type: dirichlet, components: [y], value: ['%s']}" % top]
    else:
        bcs = ["{region: bottom, type: dirichlet, components: [z], value: [0]}",
               "{region: left, type: dirichlet, components: [x], value: [0]}",
               "{region: front, type: dirichlet, components: [y], value: [0]}",
               "{region: top, type: dirichlet, components: [z], value: ['%s']}" % top]
    return T.patch_yaml(dimension, bcs, [("lo", E_LOWER, 0.0), ("up", E_UPPER, 0.0)],
                        [("lower", "lo"), ("upper", "up")], interface)


def run_blocks(dimension, geo, interface, tilt, np):
    """(rows of interface_contact.csv by node, top reaction vector, directories)."""
    work, out = T.run_case(geo, blocks_yaml(dimension, interface, tilt), np=np)
    rows = {int(r["node"]): r for r in H.read_csv(os.path.join(out, "interface_contact.csv"))}
    return rows, C.reaction(out, "top"), (work, out)


def two_blocks_surface(dimension, geo, tilt=False, np=1):
    """The surface interface against the slave/master interface with the same slave face.
    Returns the surface run's top reaction."""
    axis = dimension - 1
    rows, f_surface, dirs = run_blocks(
        dimension, geo, "{name: contact, type: contact, surface: [%s, %s]}" % FACES, tilt, np)
    # The fixed interfaces with either face as slave name the nodes of each face.
    fixed = {}
    for slave, master in (FACES, FACES[::-1]):
        fixed[slave] = run_blocks(dimension, geo, "{name: contact, type: contact, slave: %s, "
                                  "master: %s}" % (slave, master), tilt, np)
    active = set(n for n, r in rows.items() if C.is_active(r))
    slaves = [f for f in FACES if set(fixed[f][0]) == active]
    if sorted(rows) != sorted(set(fixed[FACES[0]][0]) | set(fixed[FACES[1]][0])):
        raise AssertionError("the surface interface must write one row per node of its faces")
    if len(slaves) != 1:
        raise AssertionError("the active nodes (%d) are not exactly the nodes of one face"
                             % len(active))
    slave = slaves[0]
    ref_rows, f_fixed, _ = fixed[slave]
    other = fixed[FACES[1] if slave == FACES[0] else FACES[0]][1][axis]
    print("   %d rows, %d active: slave face %s (the other face as slave gives %.15g)"
          % (len(rows), len(active), slave, other))
    for n, r in rows.items():
        if n not in active and r["normal_traction"] != 0.0:
            raise AssertionError("node %d is inactive but carries a multiplier" % n)
    scale = max(abs(r["normal_traction"]) for r in ref_rows.values())
    worst = max(abs(rows[n]["normal_traction"] - r["normal_traction"])
                for n, r in ref_rows.items()) / scale
    worst_u = max(abs(rows[n][c] - r[c]) for n, r in ref_rows.items() for c in ("ux", "uy", "uz"))
    print("   top reaction: surface %.15g, slave/master %.15g; nodal pressure max rel. diff "
          "%.2e, displacement max diff %.2e" % (f_surface[axis], f_fixed[axis], worst, worst_u))
    for c in range(dimension):
        H.assert_close(f_surface[c], f_fixed[c], rtol=1e-8, atol=1e-12 * abs(f_fixed[axis]),
                       what="top reaction component %d, surface vs slave/master" % c)
    if worst > 1e-8 or worst_u > 1e-8 * D:
        raise AssertionError("surface vs slave/master: pressure %.3e, displacement %.3e"
                             % (worst, worst_u))
    if not tilt:  # two unit-height blocks in series: sigma = d / (1/E_lower + 1/E_upper)
        H.assert_close(-f_surface[axis], D / (1.0 / E_LOWER + 1.0 / E_UPPER), rtol=1e-8,
                       what="top reaction = pressure x area")
    H.cleanup(*dirs, *fixed[FACES[0]][2], *fixed[FACES[1]][2])
    return f_surface[axis]


def test_two_blocks_surface_2d():
    geo = G.tied_rectangles(0.26, 0.11, kind="quad")
    two_blocks_surface(2, geo)
    f1 = two_blocks_surface(2, geo, tilt=True)
    f3 = two_blocks_surface(2, geo, tilt=True, np=3)
    H.assert_close(f3, f1, rtol=1e-10, what="np 3 vs np 1")


def test_two_blocks_surface_3d():
    two_blocks_surface(3, G.tied_boxes(0.35, 0.25, kind="tet"), tilt=True)


if __name__ == "__main__":
    H.main([test_two_blocks_surface_2d, test_two_blocks_surface_3d])
