"""Evaluation of seam's contact output against Hertz theory (pure Python, no numpy).

Hertz (Johnson, Contact Mechanics, 1985), frictionless, elastic body on a rigid flat,
E* = E / (1 - nu^2):
  2D cylinder, load F per unit length:  b = sqrt(4 F R / (pi E*)),  p0 = 2 F / (pi b)
  3D sphere, total load F:              a = (3 F R / (4 E*))^(1/3), p0 = 3 F / (2 pi a^2)
and in both cases p(s) = p0 sqrt(1 - s^2 / b^2), s the distance from the centre of contact.

Half-width and peak pressure from the output: the extent of the active set is quantized by the
mesh, so instead p^2 = p0^2 - (p0^2 / b^2) s^2, which is linear in s^2, is fitted by least
squares to the normal traction of the active slave nodes. Nodes whose traction is below
`edge_fraction` of the largest one are left out: the last active node carries the smeared
edge of the pressure distribution, which has an infinite slope there.

seam's normal_traction is per unit current area; small-strain theory speaks of force per
reference area at reference positions. The two differ to first order in the strain (about
0.5 p0 / E, 3 % for b/R = 0.11), so the comparison rebuilds the nodal forces D_jj lambda_j from
the mesh and divides them by the reference areas (reference_tractions).

Command line:
  python3 contact_analysis.py OUT_DIR --radius 1 --young 1 --poisson 0.3 --symmetry 2 \
      --mesh examples/hertz_2d/cylinder.geo
prints the comparison for the last step of a seam run (`--symmetry`: the factor from the
modelled part's reaction to the full load: 2 for a half cylinder, 4 for a quarter sphere;
`--reaction REGION` names the loaded Dirichlet region, `top` by default; `--mesh` the mesh the
run used, or its .geo, which is meshed again here by gmsh).
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from harness import read_csv  # noqa: E402  (shared with the other verification tests)


def is_active(row):
    s = row["status"]
    return s == 1.0 or s in ("1", "active", "stick", "slip", "tied")


def hertz_2d(force, radius, estar):
    """Half-width and peak pressure of a cylinder (force per unit length) on a flat."""
    b = math.sqrt(4.0 * force * radius / (math.pi * estar))
    return b, 2.0 * force / (math.pi * b)


def hertz_3d(force, radius, estar):
    """Contact radius and peak pressure of a sphere (total force) on a flat."""
    a = (3.0 * force * radius / (4.0 * estar)) ** (1.0 / 3.0)
    return a, 3.0 * force / (2.0 * math.pi * a * a)


def fit_semi_ellipse(s, p):
    """Least-squares fit of p^2 = A - B s^2; returns (p0, b) = (sqrt(A), sqrt(A / B))."""
    n = len(s)
    if n < 2:
        raise ValueError("need at least two points for the pressure fit, got %d" % n)
    xs = [v * v for v in s]
    ys = [v * v for v in p]
    mx = sum(xs) / n
    my = sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    if sxx == 0:
        raise ValueError("all fitted nodes lie at the same distance from the centre")
    slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx
    a = my - slope * mx
    if a <= 0 or slope >= 0:
        raise ValueError("the pressure does not decrease from the centre (A = %g, B = %g)"
                         % (a, -slope))
    return math.sqrt(a), math.sqrt(a / -slope)


def read_msh(path):
    """A Gmsh 4.1 ASCII mesh: (nodes {tag: (x, y, z)}, elements [(dim, entity, type, [tags])],
    physical groups {name: (dim, tag)}, entity physical tags {(dim, entity): [tags]})."""
    with open(path) as f:
        lines = f.read().split("\n")
    k = lines.index("$MeshFormat")
    if not lines[k + 1].startswith("4.1 0"):
        raise ValueError("%s: expected an ASCII Gmsh 4.1 mesh" % path)
    names = {}
    if "$PhysicalNames" in lines:
        k = lines.index("$PhysicalNames")
        for i in range(int(lines[k + 1])):
            f = lines[k + 2 + i].split(None, 2)
            names[f[2].strip('"')] = (int(f[0]), int(f[1]))
    k = lines.index("$Entities")
    counts = [int(v) for v in lines[k + 1].split()]
    phys = {}
    row = k + 2
    for dim, n in enumerate(counts):
        for _ in range(n):
            f = lines[row].split()
            row += 1
            nph = int(f[4 if dim == 0 else 7])
            start = 5 if dim == 0 else 8
            phys[(dim, int(f[0]))] = [int(v) for v in f[start:start + nph]]
    k = lines.index("$Nodes")
    nblocks = int(lines[k + 1].split()[0])
    row = k + 2
    nodes = {}
    for _ in range(nblocks):
        n = int(lines[row].split()[3])
        tags = [int(lines[row + 1 + i]) for i in range(n)]
        for i, t in enumerate(tags):
            nodes[t] = tuple(float(v) for v in lines[row + 1 + n + i].split()[:3])
        row += 1 + 2 * n
    k = lines.index("$Elements")
    nblocks = int(lines[k + 1].split()[0])
    row = k + 2
    elements = []
    for _ in range(nblocks):
        dim, ent, typ, n = (int(v) for v in lines[row].split())
        for i in range(n):
            elements.append((dim, ent, typ, [int(v) for v in lines[row + 1 + i].split()[1:]]))
        row += 1 + n
    return nodes, elements, names, phys


def slave_facets(msh, region):
    """Facets of a boundary region as tuples of seam node indices (seam numbers the nodes used
    by cells in increasing Gmsh tag order) and the seam index -> reference coordinates map."""
    nodes, elements, names, phys = msh
    top = max(e[0] for e in elements)
    used = sorted({t for e in elements if e[0] == top for t in e[3]})
    index = {t: i for i, t in enumerate(used)}
    dim, tag = names[region]
    facets = [tuple(index[t] for t in e[3]) for e in elements
              if e[0] == dim and tag in phys.get((dim, e[1]), [])]
    return facets, {index[t]: nodes[t] for t in used}


def _lumped(points):
    """Integral of each linear shape function over a line2, tri3 or quad4 facet."""
    def sub(a, b):
        return [a[i] - b[i] for i in range(3)]

    def cross(a, b):
        return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]

    def norm(a):
        return math.sqrt(sum(v * v for v in a))

    if len(points) == 2:
        return [0.5 * norm(sub(points[1], points[0]))] * 2
    if len(points) == 3:
        return [norm(cross(sub(points[1], points[0]), sub(points[2], points[0]))) / 6.0] * 3
    if len(points) == 4:
        g = 1.0 / math.sqrt(3.0)
        out = [0.0] * 4
        corners = ((-1, -1), (1, -1), (1, 1), (-1, 1))
        for xi in (-g, g):
            for eta in (-g, g):
                dxi = [sum(0.25 * c[0] * (1 + eta * c[1]) * p[i] for c, p in zip(corners, points))
                       for i in range(3)]
                deta = [sum(0.25 * c[1] * (1 + xi * c[0]) * p[i] for c, p in zip(corners, points))
                        for i in range(3)]
                ja = norm(cross(dxi, deta))
                for a, c in enumerate(corners):
                    out[a] += 0.25 * (1 + xi * c[0]) * (1 + eta * c[1]) * ja
        return out
    raise ValueError("facets with %d nodes are not supported" % len(points))


def reference_tractions(rows, facets):
    """Normal traction per unit *reference* area of every slave node.

    seam's normal_traction is the nodal multiplier lambda_j, per unit current area: the nodal
    force is D_jj lambda_j with D_jj the integral of the shape function over the current slave
    surface (dual multipliers; the rigid plane covers every slave facet). Small-strain theory
    (Hertz) speaks of force per reference area, and at the centre of a Hertz contact the
    surface shrinks by about 0.5 p0 / E, so the two differ by a few percent at b/R = 0.1.
    Returns ({node: traction per reference area}, sum_j D_jj lambda_j); the sum must equal
    interfaces.csv's normal_force, which checks the reconstruction of D."""
    by_node = {int(r["node"]): r for r in rows}
    d_cur, d_ref = {}, {}
    for f in facets:
        ref = [(by_node[n]["x"], by_node[n]["y"], by_node[n]["z"]) for n in f]
        cur = [(by_node[n]["x"] + by_node[n]["ux"], by_node[n]["y"] + by_node[n]["uy"],
                by_node[n]["z"] + by_node[n]["uz"]) for n in f]
        for n, wc, wr in zip(f, _lumped(cur), _lumped(ref)):
            d_cur[n] = d_cur.get(n, 0.0) + wc
            d_ref[n] = d_ref.get(n, 0.0) + wr
    out = {}
    total = 0.0
    for n, r in by_node.items():
        force = r["normal_traction"] * d_cur[n]
        total += force
        out[n] = force / d_ref[n]
    return out, total


def contact_profile(rows, dimension, current=True, tractions=None):
    """(s, p) of the active slave nodes: s the distance from the first contact point (the
    origin) in the contact plane, y = 0 in 2D (s = |x|) and z = 0 in 3D (s = sqrt(x^2 + y^2)),
    in the current configuration (x + u) unless current=False; p the normal traction, or
    tractions[node] if given."""
    out = []
    for r in rows:
        if not is_active(r):
            continue
        x = r["x"] + (r["ux"] if current else 0.0)
        y = r["y"] + (r["uy"] if current else 0.0)
        s = abs(x) if dimension == 2 else math.hypot(x, y)
        p = r["normal_traction"] if tractions is None else tractions[int(r["node"])]
        out.append((s, p))
    out.sort()
    return out


def fitted_hertz(rows, dimension, current=True, edge_fraction=0.2, tractions=None):
    """(p0, b) fitted to the active nodes' tractions (see the module docstring)."""
    prof = contact_profile(rows, dimension, current, tractions)
    if not prof:
        raise ValueError("no active slave node")
    pmax = max(p for _, p in prof)
    pts = [(s, p) for s, p in prof if p >= edge_fraction * pmax]
    return fit_semi_ellipse([s for s, _ in pts], [p for _, p in pts])


def last_step(rows):
    last = max(r["step"] for r in rows)
    return [r for r in rows if r["step"] == last]


def reaction(out_dir, region="top", component=None):
    """Force the supports of `region` exert on the body at the last step (vector)."""
    rows = [r for r in last_step(read_csv(os.path.join(out_dir, "reactions.csv")))
            if r["region"] == region]
    if not rows:
        raise ValueError("no reaction row for region %r in %s" % (region, out_dir))
    f = (rows[0]["fx"], rows[0]["fy"], rows[0]["fz"])
    return f if component is None else f[component]


def convergence_orders(residuals, floor):
    """Observed orders log(r[k+1]/r[k]) / log(r[k]/r[k-1]) for the triples whose last
    residual is still above `floor` (below it round-off dominates)."""
    orders = []
    for k in range(1, len(residuals) - 1):
        r0, r1, r2 = residuals[k - 1], residuals[k], residuals[k + 1]
        if min(r0, r1, r2) <= 0 or r2 <= floor or r1 >= r0:
            continue
        orders.append(math.log(r2 / r1) / math.log(r1 / r0))
    return orders


def newton_table(out_dir):
    """{step: [(iteration, residual, increment, active_set_changes), ...]} of the converged
    attempts (the last attempt of each step number)."""
    table = {}
    for r in read_csv(os.path.join(out_dir, "newton.csv")):
        step = int(r["step"])
        it = int(r["iteration"])
        rows = table.setdefault(step, [])
        if it == 0:
            rows.clear()  # a new attempt at this step after a cut
        rows.append((it, r["residual"], r["increment"], int(r["active_set_changes"])))
    return table


def mesh_geo(geo, dimension, msh):
    """Meshes a .geo with the gmsh executable (seam meshes with the same library)."""
    import subprocess
    p = subprocess.run([os.environ.get("GMSH", "gmsh"), "-%d" % dimension, "-format", "msh41",
                        "-o", msh, geo], capture_output=True, text=True)
    if p.returncode != 0 or not os.path.exists(msh):
        raise RuntimeError("gmsh failed on %s:\n%s" % (geo, p.stdout[-2000:]))
    return msh


def report(out_dir, radius, young, poisson, symmetry, region="top", mesh=None, slave="surface"):
    name = [f for f in os.listdir(out_dir) if f.startswith("interface_")][0]
    rows = read_csv(os.path.join(out_dir, name))
    dimension = 3 if any(abs(r["z"]) > 0 for r in rows) else 2
    estar = young / (1.0 - poisson ** 2)
    force = abs(reaction(out_dir, region, dimension - 1)) * symmetry
    ref = hertz_2d(force, radius, estar) if dimension == 2 else hertz_3d(force, radius, estar)
    print("load F = %.6g (%s, %dD), E* = %.6g" % (force, "per unit length" if dimension == 2
                                                   else "total", dimension, estar))
    fits = [("current area, current positions", fitted_hertz(rows, dimension))]
    if mesh:
        if mesh.endswith(".geo"):
            import tempfile
            mesh = mesh_geo(mesh, dimension, os.path.join(tempfile.mkdtemp(), "mesh.msh"))
        facets, _ = slave_facets(read_msh(mesh), slave)
        tractions, total = reference_tractions(rows, facets)
        normal_force = last_step(read_csv(os.path.join(out_dir, "interfaces.csv")))[0]
        print("sum of D_jj lambda_j %.12g, interfaces.csv normal_force %.12g"
              % (total, normal_force["normal_force"]))
        fits.append(("reference area, reference positions",
                     fitted_hertz(rows, dimension, current=False, tractions=tractions)))
    print("%-36s %-18s %10s %10s %8s" % ("fit", "", "Hertz", "seam", "error"))
    for what, (p0, b) in fits:
        for name, r, v in (("half-width/radius", ref[0], b), ("peak pressure", ref[1], p0)):
            print("%-36s %-18s %10.6g %10.6g %+7.2f%%" % (what, name, r, v, 100.0 * (v - r) / r))
    active = [r for r in rows if is_active(r)]
    print("%d active nodes, largest nodal traction %.6g, b/R = %.3f"
          % (len(active), max(r["normal_traction"] for r in active), ref[0] / radius))
    for step, its in sorted(newton_table(out_dir).items()):
        print("step %d: %d iterations, residuals %s, active-set changes %s" % (
            step, len(its) - 1, " ".join("%.1e" % it[1] for it in its),
            " ".join(str(it[3]) for it in its)))


def main(argv):
    import argparse
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("out_dir")
    ap.add_argument("--radius", type=float, default=1.0)
    ap.add_argument("--young", type=float, default=1.0)
    ap.add_argument("--poisson", type=float, default=0.3)
    ap.add_argument("--symmetry", type=float, default=1.0,
                    help="full load / load on the model (2 half cylinder, 4 quarter sphere)")
    ap.add_argument("--reaction", default="top", help="loaded Dirichlet region")
    ap.add_argument("--mesh", help="the run's .msh (or .geo, meshed here): adds the fit of the "
                    "traction per reference area")
    ap.add_argument("--slave", default="surface", help="slave region (with --mesh)")
    a = ap.parse_args(argv)
    report(a.out_dir, a.radius, a.young, a.poisson, a.symmetry, a.reaction, a.mesh, a.slave)


if __name__ == "__main__":
    main(sys.argv[1:])
