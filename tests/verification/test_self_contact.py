"""Self and multi-body contact (`surface: [groups...]`): slave and master facets chosen at
every search.

- Two blocks pressed together (2D quads and 3D tetrahedra, non-matching meshes, nu = 0) as one
  `surface:` interface over both contact faces, the top pushed down uniformly (pressure
  d / sum(H_i / E_i), analytic) or tilted (a non-uniform pressure whose mortar solution depends
  on the slave face): the active nodes are exactly the nodes of one face, the other face's
  nodes carry no multiplier, and nodal pressures, tangential tractions, displacements and the
  top reaction equal those of the slave/master interface with that face as slave to 1e-8
  (the other face as slave differs by 2.5e-7); dual and standard multipliers, Coulomb
  friction, line3 faces, np = 3 equals np = 1; tri6 faces with SEAM_FULL=1.
- A ring (2D annulus) squeezed between two rigid planes until its inner surface closes onto
  itself (one `surface:` interface over the inner circle): the left-right mirror symmetry holds
  to 1e-7 of the radius, the top-bottom one to 2e-3 (the one-sided mortar at the folds, see
  ring_case), no node of one half of the hole lies beyond the other half by more than 1e-6 of
  the radius, the inner contact force is positive, the two plane forces balance to 1e-8;
  np = 3 equals np = 1. The same ring extruded into hexahedra in plane strain (3D self
  contact of quad4 faces) gives the 2D forces per unit thickness within 1e-4.
- Bar impact: two equal elastic bars (E = rho = 1, nu = 0, 40 x 2 quads each) end on, bar a at
  v onto bar b at rest, as one `surface:` interface over both bars' whole boundaries and as a
  two-body interface between the ends, with generalized-alpha and the energy-momentum scheme:
  contact lasts 2 L / c within two steps, the contact stress is rho c v / 2 within 2 %, the
  bars leave with the velocities exchanged (within 3 % of v), momentum is constant to 1e-10,
  the energy-momentum scheme never gains energy, generalized-alpha gains at most 1e-4 in a
  step; the two interfaces give the same contact force history to 1e-8; np = 3 equals np = 1.
- Bad `surface:` input (combined with slave/master/rigid_plane, on mesh tying, empty, a group
  twice, missing or of the wrong dimension): exit 1 with a located message.
"""
import os
import sys
import tempfile

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


def two_blocks_surface(dimension, geo, tilt=False, np=1, options=""):
    """The surface interface against the slave/master interface with the same slave face
    (`options`: more keys of both interfaces). Returns the surface run's top reaction."""
    axis = dimension - 1
    rows, f_surface, dirs = run_blocks(
        dimension, geo, "{name: contact, type: contact, surface: [%s, %s]%s}"
        % (FACES + (options,)), tilt, np)
    # The fixed interfaces with either face as slave name the nodes of each face.
    fixed = {}
    for slave, master in (FACES, FACES[::-1]):
        fixed[slave] = run_blocks(dimension, geo, "{name: contact, type: contact, slave: %s, "
                                  "master: %s%s}" % (slave, master, options), tilt, np)
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
    worst = max(abs(rows[n][c] - r[c]) for n, r in ref_rows.items()
                for c in ("normal_traction", "tangential_traction")) / scale
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


def test_held_pairs_follow_the_state():
    """Pairs held by the pair cycling guard (forced from each step's second search by
    SEAM_HOLD_SELF_PAIRS=1) are integrated at the current positions: the two blocks equal the
    slave/master interface, at np 1 and 3."""
    geo = G.tied_rectangles(0.26, 0.11, kind="quad")
    os.environ["SEAM_HOLD_SELF_PAIRS"] = "1"
    try:
        f1 = two_blocks_surface(2, geo, tilt=True)
        f3 = two_blocks_surface(2, geo, tilt=True, np=3)
    finally:
        del os.environ["SEAM_HOLD_SELF_PAIRS"]
    H.assert_close(f3, f1, rtol=1e-10, what="np 3 vs np 1")


def test_two_blocks_surface_2d():
    geo = G.tied_rectangles(0.26, 0.11, kind="quad")
    two_blocks_surface(2, geo)
    f1 = two_blocks_surface(2, geo, tilt=True)
    f3 = two_blocks_surface(2, geo, tilt=True, np=3)
    H.assert_close(f3, f1, rtol=1e-10, what="np 3 vs np 1")


def test_two_blocks_surface_standard_friction_quadratic():
    """Standard multipliers (saddle point), Coulomb friction (mu = 0.3; the tilted top makes
    the faces slide) and quadratic faces (line3) on the surface interface, 2D."""
    geo = G.tied_rectangles(0.26, 0.11, kind="quad")
    two_blocks_surface(2, geo, tilt=True, options=", multiplier: standard")
    two_blocks_surface(2, geo, tilt=True, options=", friction: {model: coulomb, coefficient: 0.3}")
    two_blocks_surface(2, G.tied_rectangles(0.26, 0.11, order=2, kind="quad"), tilt=True)


@H.full_only
def test_two_blocks_surface_3d_tet10():
    """tri6 faces (modified dual basis) on the surface interface."""
    two_blocks_surface(3, G.tied_boxes(0.5, 0.35, order=2, kind="tet"), tilt=True)


def test_two_blocks_surface_3d():
    two_blocks_surface(3, G.tied_boxes(0.35, 0.25, kind="tet"), tilt=True)


# ---------------------------------------------------------------------------------------------
# A ring squeezed between two rigid planes until its inner surface closes onto itself

RING_GEO = """R = 1.0; r = 0.6; nc = NC; nr = NR;
Point(1) = {0, 0, 0};
Point(2) = {R, 0, 0}; Point(3) = {0, R, 0}; Point(4) = {-R, 0, 0}; Point(5) = {0, -R, 0};
Point(6) = {r, 0, 0}; Point(7) = {0, r, 0}; Point(8) = {-r, 0, 0}; Point(9) = {0, -r, 0};
Circle(1) = {2, 1, 3}; Circle(2) = {3, 1, 4}; Circle(3) = {4, 1, 5}; Circle(4) = {5, 1, 2};
Circle(5) = {6, 1, 7}; Circle(6) = {7, 1, 8}; Circle(7) = {8, 1, 9}; Circle(8) = {9, 1, 6};
Line(9) = {6, 2}; Line(10) = {7, 3}; Line(11) = {8, 4}; Line(12) = {9, 5};
Curve Loop(1) = {9, 1, -10, -5}; Plane Surface(1) = {1};
Curve Loop(2) = {10, 2, -11, -6}; Plane Surface(2) = {2};
Curve Loop(3) = {11, 3, -12, -7}; Plane Surface(3) = {3};
Curve Loop(4) = {12, 4, -9, -8}; Plane Surface(4) = {4};
Transfinite Curve{1:8} = nc + 1;
Transfinite Curve{9:12} = nr + 1;
Transfinite Surface{1:4}; Recombine Surface{1:4};
Physical Surface("ring") = {1:4};
Physical Curve("outer_top") = {1, 2};
Physical Curve("outer_bottom") = {3, 4};
Physical Curve("inner") = {5:8};
Physical Point("north") = {3};
Physical Point("south") = {5};
"""

# Neo-Hooke ring, outer radius 1, inner 0.6; each plane moves 0.65 towards the centre, which
# closes the hole (its inner top and bottom meet after about 0.6 of travel each, first at the
# folds near (+-0.6, 0), then along the whole slit).
RING_YAML = """dimension: 2
mesh: {geo: case.geo}
materials:
  rubber: {model: neo_hooke, young: 100, poisson: 0.3}
bodies:
  - {region: ring, material: rubber}
boundary_conditions:
  - {region: north, type: dirichlet, components: [x], value: [0]}
  - {region: south, type: dirichlet, components: [x], value: [0]}
interfaces:
  - {name: top, type: contact, slave: outer_top,
     rigid_plane: {point: [0, 1], normal: [0, -1], motion: ["0", "-0.65*t"]}}
  - {name: bottom, type: contact, slave: outer_bottom,
     rigid_plane: {point: [0, -1], normal: [0, 1], motion: ["0", "0.65*t"]}}
  - {name: inner, type: contact, surface: [inner]}
time: {integrator: static, end: 1, steps: STEPS}
solver: {newton: {tolerance: 1.0e-11, max_iterations: 30}}
output: {every: STEPS}
"""


def last_interface_rows(out):
    """interfaces.csv at the last step, by interface name."""
    rows = H.last_step_rows(H.read_csv(os.path.join(out, "interfaces.csv")))
    return {r["interface"]: r for r in rows}


def ring_nodes(out):
    """(reference x, y, ux, uy) of every node of the three interfaces."""
    nodes = {}
    for name in ("top", "bottom", "inner"):
        for r in H.read_csv(os.path.join(out, "interface_%s.csv" % name)):
            nodes[int(r["node"])] = (r["x"], r["y"], r["ux"], r["uy"])
    return list(nodes.values())


def mirror_of(nodes, x, y):
    """The node at reference position (x, y) (the mesh is symmetric to round-off)."""
    best = min(nodes, key=lambda n: (n[0] - x) ** 2 + (n[1] - y) ** 2)
    if (best[0] - x) ** 2 + (best[1] - y) ** 2 > 1e-14:
        raise AssertionError("no node at (%r, %r): the mesh is not symmetric" % (x, y))
    return best


def ring_case(np=1, nc=24, nr=6, steps=60):
    work, out = T.run_case(RING_GEO.replace("NC", str(nc)).replace("NR", str(nr)),
                           RING_YAML.replace("STEPS", str(steps)), np=np)
    radius = 1.0
    itf = last_interface_rows(out)
    f_top, f_bottom, f_inner = (itf[n]["normal_force"] for n in ("top", "bottom", "inner"))
    print("   plane forces %.15g, %.15g; inner contact force %.10g on %d active nodes"
          % (f_top, f_bottom, f_inner, itf["inner"]["active_nodes"]))
    if not (f_inner > 0.0 and itf["inner"]["active_nodes"] > 0):
        raise AssertionError("the inner surface did not close onto itself")
    H.assert_close(f_top, f_bottom, rtol=1e-8, what="force balance: top plane vs bottom plane")
    fx = sum(abs(C.reaction(out, p, 0)) for p in ("north", "south"))
    H.assert_close(fx, 0.0, atol=1e-8 * f_top, what="x reactions of the pinned points")
    # Both mirror symmetries: u(-x, y) = (-ux, uy), u(x, -y) = (ux, -uy). The left-right one
    # holds to the mesh's round-off (Gmsh places mirrored arc nodes 1e-9 apart). The top-bottom
    # one is broken by the one-sided mortar at the folds, where the slave (upper) facets project
    # along their own normals onto the lower ones: the closed slit settles 4e-5 below y = 0 and
    # the folded ends, which hinge freely, tilt by up to 1e-3 of the radius (24 x 6 cells).
    nodes = ring_nodes(out)
    worst = [0.0, 0.0]
    for x, y, ux, uy in nodes:
        for k, (sx, sy) in enumerate(((-1, 1), (1, -1))):
            _, _, mx, my = mirror_of(nodes, sx * x, sy * y)
            worst[k] = max(worst[k], abs(mx - sx * ux), abs(my - sy * uy))
    print("   symmetry: max deviation left-right %.2e, top-bottom %.2e (of the radius)"
          % (worst[0] / radius, worst[1] / radius))
    if worst[0] > 1e-7 * radius or worst[1] > 2e-3 * radius:
        raise AssertionError("the solution breaks the symmetry by %.3e, %.3e" % tuple(worst))
    # No penetration: every node of the upper inner half lies on or above the lower inner half
    # (the polyline of its deformed nodes) where they overlap, and the reverse; the mortar gaps
    # of the active nodes are not negative.
    inner = H.read_csv(os.path.join(out, "interface_inner.csv"))

    def polyline(rows):
        return sorted((r["x"] + r["ux"], r["y"] + r["uy"]) for r in rows)

    upper = polyline(r for r in inner if r["y"] > 0.0 and r["x"] ** 2 < 0.5 ** 2)
    lower = polyline(r for r in inner if r["y"] < 0.0 and r["x"] ** 2 < 0.5 ** 2)

    def below(points, line):  # largest depth of a point under the polyline `line`
        depth = -1e300
        for px, py in points:
            for (ax, ay), (bx, by) in zip(line, line[1:]):
                if ax <= px <= bx and bx > ax:
                    depth = max(depth, ay + (by - ay) * (px - ax) / (bx - ax) - py)
        return depth

    pen = max(below(upper, lower), -below(lower, upper))
    gaps = min(r["gap"] for r in inner if C.is_active(r))
    print("   penetration %.2e, smallest active nodal gap %.2e (of the radius)"
          % (pen / radius, gaps / radius))
    if pen > 1e-6 * radius or gaps < -1e-6 * radius:
        raise AssertionError("penetration %.3e, gap %.3e beyond 1e-6 of the radius" % (pen, gaps))
    H.cleanup(work, out)
    return f_top, f_inner


def test_ring_closes_onto_itself():
    f1 = ring_case(steps=30)
    f3 = ring_case(steps=30, np=3)
    for a, b, what in zip(f3, f1, ("plane force", "inner force")):
        H.assert_close(a, b, rtol=1e-8, what="%s np 3 vs np 1" % what)


def ring_3d_yaml():
    """The ring extruded by 0.2 (one layer of hexahedra) with w = 0 on both faces: plane strain,
    so the 3D solution per unit thickness is the 2D one up to the 3D mortar's projection onto
    auxiliary planes."""
    y = RING_YAML.replace("dimension: 2", "dimension: 3")
    y = y.replace("""  - {region: south, type: dirichlet, components: [x], value: [0]}""",
                  """  - {region: south, type: dirichlet, components: [x], value: [0]}
  - {region: front, type: dirichlet, components: [z], value: [0]}
  - {region: back, type: dirichlet, components: [z], value: [0]}""")
    for a, b in (('point: [0, 1], normal: [0, -1], motion: ["0", "-0.65*t"]',
                  'point: [0, 1, 0], normal: [0, -1, 0], motion: ["0", "-0.65*t", "0"]'),
                 ('point: [0, -1], normal: [0, 1], motion: ["0", "0.65*t"]',
                  'point: [0, -1, 0], normal: [0, 1, 0], motion: ["0", "0.65*t", "0"]')):
        y = y.replace(a, b)
    return y


def ring_3d_geo(nc, nr):
    geo = RING_GEO.replace("NC", str(nc)).replace("NR", str(nr))
    return geo[:geo.find('Physical Surface("ring")')] + """\
out[] = Extrude {0, 0, 0.2} { Surface{1:4}; Layers{1}; Recombine; };
Physical Volume("ring") = {out[1], out[7], out[13], out[19]};
Physical Surface("outer_top") = {out[3], out[9]};
Physical Surface("outer_bottom") = {out[15], out[21]};
Physical Surface("inner") = {out[5], out[11], out[17], out[23]};
Physical Surface("front") = {1:4};
Physical Surface("back") = {out[0], out[6], out[12], out[18]};
Physical Point("north") = {3};
Physical Point("south") = {5};
"""


def test_ring_3d_equals_2d():
    """3D self contact (quad4 faces): the extruded ring in plane strain against the 2D ring on
    the same section mesh (16 x 4 cells): forces per unit thickness within 1e-4, the hole
    closed over twice as many nodes."""
    nc, nr, steps = 16, 4, 30
    work, out = T.run_case(RING_GEO.replace("NC", str(nc)).replace("NR", str(nr)),
                           RING_YAML.replace("STEPS", str(steps)))
    ref = last_interface_rows(out)
    work3, out3 = T.run_case(ring_3d_geo(nc, nr), ring_3d_yaml().replace("STEPS", str(steps)))
    got = last_interface_rows(out3)
    for name in ("top", "bottom", "inner"):
        f2, f3 = ref[name]["normal_force"], got[name]["normal_force"] / 0.2
        print("   %s: 2D %.10g, 3D per thickness %.10g (rel. diff %.1e); active nodes %d, %d"
              % (name, f2, f3, abs(f3 - f2) / f2, ref[name]["active_nodes"],
                 got[name]["active_nodes"]))
        H.assert_close(f3, f2, rtol=1e-4, what="%s force per thickness 3D vs 2D" % name)
        if got[name]["active_nodes"] != 2 * ref[name]["active_nodes"]:
            raise AssertionError("%s: %d active nodes in 3D, %d in 2D" % (
                name, got[name]["active_nodes"], ref[name]["active_nodes"]))
    H.assert_close(got["top"]["normal_force"], got["bottom"]["normal_force"], rtol=1e-8,
                   what="3D force balance")
    H.cleanup(work, out, work3, out3)


# ---------------------------------------------------------------------------------------------
# Bar impact: two equal elastic bars (nu = 0) end on

BAR_GEO = """L = 1.0; H = 0.1; g = GAP; nx = NX; ny = 2;
Point(1) = {0, 0, 0}; Point(2) = {L, 0, 0}; Point(3) = {L, H, 0}; Point(4) = {0, H, 0};
Point(5) = {L + g, 0, 0}; Point(6) = {2 * L + g, 0, 0}; Point(7) = {2 * L + g, H, 0};
Point(8) = {L + g, H, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, 8}; Plane Surface(2) = {2};
Transfinite Curve{1, 3, 5, 7} = nx + 1; Transfinite Curve{2, 4, 6, 8} = ny + 1;
Transfinite Surface{1, 2}; Recombine Surface{1, 2};
Physical Surface("bar_a") = {1}; Physical Surface("bar_b") = {2};
Physical Curve("a_end") = {2}; Physical Curve("b_end") = {8};
Physical Curve("a_boundary") = {1, 2, 3, 4}; Physical Curve("b_boundary") = {5, 6, 7, 8};
"""

# E = rho = 1 (c = 1), nu = 0: each bar is a 1D rod. Bar a flies at v = 0.01 onto bar b at
# rest, the gap 0.01 closes at t = 1; the contact lasts 2 L / c = 2 with the stress rho c v / 2
# (the interface moves at v / 2), after which a rests and b flies at v.
BAR_YAML = """dimension: 2
mesh: {geo: case.geo}
materials:
  m: {model: linear_elastic, young: 1, poisson: 0, density: 1}
bodies:
  - {region: bar_a, material: m}
  - {region: bar_b, material: m}
initial_conditions:
  - {region: bar_a, velocity: ["0.01", "0"]}
interfaces:
  - INTERFACE
time: {integrator: INTEGRATOR, end: 4, steps: STEPS}
solver: {newton: {tolerance: 1.0e-12, max_iterations: 30}}
output: {every: 1000, probes: [[0.5, 0.05], [1.51, 0.05]]}
"""
BAR_SURFACE = "{name: impact, type: contact, surface: [a_boundary, b_boundary]}"
BAR_TWO_BODY = "{name: impact, type: contact, slave: a_end, master: b_end}"


def bar_impact(interface, integrator, nx=40, steps=160, np=1, gap=0.01, order=1):
    v, c, L, height = 0.01, 1.0, 1.0, 0.1
    dt = 4.0 / steps
    geo = BAR_GEO.replace("GAP", repr(gap)).replace("NX", str(nx))
    if order == 2:
        geo += "Mesh.ElementOrder = 2;\n"
    yaml = BAR_YAML.replace("INTERFACE", interface).replace("INTEGRATOR", integrator)
    work, out = T.run_case(geo, yaml.replace("STEPS", str(steps)), np=np)
    steps_rows = H.read_csv(os.path.join(out, "steps.csv"))
    itf = [r for r in H.read_csv(os.path.join(out, "interfaces.csv"))]
    probes = H.read_csv(os.path.join(out, "probes.csv"))
    H.cleanup(work, out)
    touching = [r for r in itf if r["normal_force"] > 0.0]
    t_first, t_last = touching[0]["time"], touching[-1]["time"]
    duration = t_last - t_first  # from the first to the last step end with a contact force
    plateau = [r["normal_force"] / height for r in touching
               if t_first + 0.25 < r["time"] < t_last - 0.25]
    sigma = sum(plateau) / len(plateau)
    spread = (max(plateau) - min(plateau)) / sigma
    # Velocities from the probes at the bars' middles over the last second (after separation).
    vel = []
    for p in (0, 1):
        rows = [r for r in probes if r["probe"] == p]
        a, b = rows[-41], rows[-1]
        vel.append((b["ux"] - a["ux"]) / (b["time"] - a["time"]))
    e = [r["total_energy"] for r in steps_rows]
    e0 = 0.5 * v * v * L * height
    rise = max(b - a for a, b in zip([e0] + e, e)) / e0
    mom = max(abs(r["momentum_x"] - v * L * height) for r in steps_rows) / (v * L * height)
    # No loads, supports or rigid obstacles: the bars' contact forces on each other are
    # internal, so external_work stays zero and total_energy shows what the impact dissipates.
    external = max(abs(r["external_work"]) for r in steps_rows) / e0
    if external > 1e-10:
        raise AssertionError("external_work reaches %.3e of the energy: the bars' contact "
                             "forces on each other counted as external" % external)
    print("   %s, %s: contact %.3f .. %.3f, duration %.4f (2L/c = 2, %.1f steps off), contact "
          "stress %.6g (rho c v / 2 = %.6g, plateau spread %.1f %%); velocities after %.5f, "
          "%.5f (0, %.2f); energy end/start %.6f, largest rise in a step %.2e of it; momentum "
          "drift %.1e" % ("surface" if "surface" in interface else "two-body", integrator,
                          t_first, t_last, duration,
                          abs(duration - 2 * L / c) / dt, sigma, v / 2, 100 * spread, vel[0],
                          vel[1], v, e[-1] / e0, rise, mom))
    return dict(duration=duration, dt=dt, sigma=sigma, vel=vel, rise=rise, mom=mom,
                energy=e[-1] / e0, force=[r["normal_force"] for r in itf])


def check_bar(r, integrator, v=0.01):
    if abs(r["duration"] - 2.0) > 2 * r["dt"]:
        raise AssertionError("contact lasted %.4f, not 2 L / c = 2 within two steps"
                             % r["duration"])
    H.assert_close(r["sigma"], v / 2, rtol=0.02, what="contact stress rho c v / 2")
    H.assert_close(r["vel"][0], 0.0, atol=0.03 * v, what="velocity of bar a after the impact")
    H.assert_close(r["vel"][1], v, rtol=0.03, what="velocity of bar b after the impact")
    H.assert_close(r["mom"], 0.0, atol=1e-10, what="momentum drift")
    # The energy-momentum scheme never gains energy through the impact. Generalized-alpha
    # (rho_inf = 0.8) may gain at most 1e-4 of it in a step (issue 13). Carrying the Newmark
    # acceleration of the step in which the bars separate into the next one made it gain
    # 1.03e-4 two steps after the separation (the highest modes of the bars, excited by the
    # jump of the contact force); generalized-alpha now restarts from the acceleration of
    # equilibrium after every change of the contact set (dynamic_solver.cpp).
    bound = 1e-12 if integrator == "energy_momentum" else 1e-4
    if r["rise"] > bound:
        raise AssertionError("a step gained %.2e of the energy (> %.1e)" % (r["rise"], bound))


def test_bar_impact():
    """The bars meet 0.6 of a step into step 42 (gap 0.01015): the worst touch point measured
    for generalized-alpha's energy."""
    results = {}
    gap = 0.01015
    for name, itf in (("surface", BAR_SURFACE), ("two_body", BAR_TWO_BODY)):
        for integrator in ("generalized_alpha", "energy_momentum"):
            results[name, integrator] = bar_impact(itf, integrator, gap=gap)
            check_bar(results[name, integrator], integrator)
    for integrator in ("generalized_alpha", "energy_momentum"):
        a, b = results["surface", integrator], results["two_body", integrator]
        worst = max(abs(x - y) for x, y in zip(a["force"], b["force"])) / max(b["force"])
        print("   %s: surface vs two-body contact force, max rel. diff %.2e" % (integrator, worst))
        if worst > 1e-8:
            raise AssertionError("surface and two-body interfaces differ by %.3e" % worst)
    r3 = bar_impact(BAR_SURFACE, "generalized_alpha", gap=gap, np=3)
    a = results["surface", "generalized_alpha"]
    worst = max(abs(x - y) for x, y in zip(r3["force"], a["force"])) / max(a["force"])
    print("   np 3 vs np 1 contact force, max rel. diff %.2e" % worst)
    if worst > 1e-8 or len(r3["force"]) != len(a["force"]):
        raise AssertionError("np 3 differs from np 1 by %.3e" % worst)


def test_surface_bad_input():
    """A `surface:` interface with slave, master or rigid_plane, on mesh tying, empty, with a
    group twice, a missing group or a group of the wrong dimension: exit 1 with a located
    message."""
    base = RING_YAML.replace("STEPS", "1")
    work = tempfile.mkdtemp(prefix="seam_self_bad_")
    H.write_case(work, "case.geo", RING_GEO.replace("NC", "8").replace("NR", "2"))
    cases = [
        ("surface: [inner], slave: inner", "interfaces[2].slave: 'slave' cannot be combined"),
        ("surface: [inner], master: inner", "interfaces[2].master: 'master' cannot be combined"),
        ("surface: [inner], rigid_plane: {point: [0, 0], normal: [0, 1]}",
         "interfaces[2].rigid_plane: 'rigid_plane' cannot be combined"),
        ("surface: []", "interfaces[2].surface: expected a list of one or more boundary groups"),
        ("surface: [inner, inner]", "interfaces[2].surface[1]: group 'inner' is listed twice"),
        ("surface: [nothere]", "interfaces[2].surface[0]: no region 'nothere'"),
        ("surface: [ring]", "interfaces[2].surface[0]: region 'ring' has dimension 2"),
    ]
    for keys, expected in cases + [("surface: [inner]", "")]:
        text = base.replace("{name: inner, type: contact, surface: [inner]}",
                            "{name: inner, type: contact, %s}" % keys)
        path = H.write_case(work, "case.yaml", text)
        code, out, err = H.run(["check", path], check=False)
        if expected and (code != 1 or expected not in out + err):
            raise AssertionError("%s: exit %d, %r; expected exit 1 and %r"
                                 % (keys, code, (out + err)[-300:], expected))
        if not expected and code != 0:
            raise AssertionError("the valid input fails: %s" % (out + err)[-300:])
    text = base.replace("type: contact, surface: [inner]", "type: mesh_tying, surface: [inner]")
    code, out, err = H.run(["check", H.write_case(work, "case.yaml", text)], check=False)
    if code != 1 or "'surface' applies only to type 'contact'" not in out + err:
        raise AssertionError("mesh tying with surface: exit %d, %r" % (code, (out + err)[-300:]))
    H.cleanup(work)


if __name__ == "__main__":
    H.main([test_two_blocks_surface_2d, test_held_pairs_follow_the_state,
            test_two_blocks_surface_standard_friction_quadratic,
            test_two_blocks_surface_3d, test_two_blocks_surface_3d_tet10,
            test_ring_closes_onto_itself, test_ring_3d_equals_2d, test_bar_impact,
            test_surface_bad_input])
