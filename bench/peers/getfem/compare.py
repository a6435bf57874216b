#!/usr/bin/env python3
"""seam against GetFEM on the same problem (issue 16, benchmark 2), side by side.

The problem: examples/hertz_3d, a quarter of the lower half of an elastic sphere (R = 1, E = 1,
nu = 0.3, linear elasticity) pressed onto the rigid plane z = 0 by moving its cut z = 1 down by
0.015, x = 0 and y = 0 symmetry planes; frictionless. One quadratic tetrahedral mesh (tet10,
isoparametric) of examples/hertz_3d/sphere.geo with `refine` (default 1.65: 73,977 dofs),
meshed once by gmsh here and read by both codes.

  GetFEM: hertz_getfem.py (integral contact brick, Alart-Curnier, MUMPS), /usr/bin/python3.
  seam:   mortar contact with dual multipliers against the rigid plane, `solver.linear` as
          chosen (--linear, default: seam's default), one rank.

Both use the same number of load steps (--steps, default 1: the problem is path-independent)
and the same relative Newton tolerance (--tolerance). Accuracy: the load F (four times the
reaction of the cut for seam, the integral of the contact pressure for GetFEM), the contact
radius a and peak pressure p0 fitted to the nodal contact pressures per reference area
(p^2 = p0^2 (1 - r^2/a^2), nodes above 0.2 p_max; tests/verification/contact_analysis.py),
against Hertz for each code's own F: a = (3 F R / (4 E*))^(1/3), p0 = 3 F / (2 pi a^2).
Wall time: the whole process measured from outside (mesh reading, set-up, solve; seam also
writes its output once).

  sh bench/peers/getfem/setup.sh
  python3 bench/peers/getfem/compare.py --seam build/bin/seam [--refine 1.65] [--steps 1]
"""
import argparse
import json
import math
import os
import resource
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(HERE)))
sys.path.insert(0, os.path.join(ROOT, "tests", "verification"))
import contact_analysis as ca  # noqa: E402
from harness import read_csv  # noqa: E402

R, YOUNG, POISSON = 1.0, 1.0, 0.3
ESTAR = YOUNG / (1 - POISSON ** 2)

YAML = """title: Hertz quarter sphere, tet10 (bench/peers/getfem)
dimension: 3
mesh: {{file: {mesh}}}
materials:
  elastic: {{model: linear_elastic, young: 1, poisson: 0.3}}
bodies:
  - {{region: sphere, material: elastic}}
boundary_conditions:
  - {{region: symmetry_x, type: dirichlet, components: [x], value: [0]}}
  - {{region: symmetry_y, type: dirichlet, components: [y], value: [0]}}
  - {{region: top, type: dirichlet, components: [z], value: ["-0.015*t"]}}
interfaces:
  - name: contact
    type: contact
    slave: surface
    rigid_plane: {{point: [0, 0, 0], normal: [0, 0, 1], motion: ["0", "0", "0"]}}
    multiplier: dual
time: {{integrator: static, end: 1, steps: {steps}}}
solver:
  linear: {linear}
  newton: {{tolerance: {tolerance}, max_iterations: 50}}
output: {{every: {steps}}}
"""


def mesh(work, refine):
    """sphere.geo with `refine`, quadratic; the same mesh in Gmsh 2.2 (GetFEM) and 4.1 (seam and
    contact_analysis.read_msh)."""
    geo = open(os.path.join(ROOT, "examples", "hertz_3d", "sphere.geo")).read()
    if "refine = 1;" not in geo:
        sys.exit("sphere.geo: no 'refine = 1;' line to set")
    path = os.path.join(work, "sphere.geo")
    open(path, "w").write(geo.replace("refine = 1;", "refine = %s;" % refine, 1))
    m22, m41 = os.path.join(work, "sphere22.msh"), os.path.join(work, "sphere41.msh")
    subprocess.run(["gmsh", "-3", "-order", "2", path, "-format", "msh22", "-o", m22],
                   check=True, capture_output=True)
    subprocess.run(["gmsh", m22, "-0", "-format", "msh41", "-o", m41], check=True,
                   capture_output=True)
    return m22, m41


def timed(cmd, **kw):
    """Runs cmd; (stdout, wall seconds, CPU seconds of the process and its children)."""
    t = time.perf_counter()
    c = resource.getrusage(resource.RUSAGE_CHILDREN)
    p = subprocess.run(cmd, capture_output=True, text=True, **kw)
    wall = time.perf_counter() - t
    d = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = d.ru_utime + d.ru_stime - c.ru_utime - c.ru_stime
    if p.returncode != 0:
        sys.exit("%s failed (%d):\n%s\n%s" % (cmd[0], p.returncode, p.stdout[-3000:],
                                              p.stderr[-3000:]))
    return p.stdout, wall, cpu


def run_getfem(python, msh, steps, tolerance, r):
    out, wall, cpu = timed([python, os.path.join(HERE, "hertz_getfem.py"), msh, "--steps", str(steps),
                       "--tolerance", str(tolerance), "--r", str(r)])
    res = json.loads(out.strip().splitlines()[-1])
    res["wall"], res["cpu"] = wall, cpu
    res["own"] = res["total"]
    return res


def reference_tractions(rows, facets):
    """seam's normal_traction (per current area) per unit reference area: times the surface
    stretch at the node, the mean current / reference area of the corner triangles of its
    facets (contact_analysis.reference_tractions rebuilds D_jj, which needs linear facets)."""
    by_node = {int(r["node"]): r for r in rows}

    def area(pts):
        u = [pts[1][i] - pts[0][i] for i in range(3)]
        v = [pts[2][i] - pts[0][i] for i in range(3)]
        return math.sqrt(sum(c * c for c in (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                                             u[0] * v[1] - u[1] * v[0])))
    stretch = {}
    for f in facets:
        rs = [by_node[n] for n in f[:3]]
        ref = [(r["x"], r["y"], r["z"]) for r in rs]
        cur = [(r["x"] + r["ux"], r["y"] + r["uy"], r["z"] + r["uz"]) for r in rs]
        ratio = area(cur) / area(ref)
        for n in f:
            stretch.setdefault(n, []).append(ratio)
    return {n: r["normal_traction"] * sum(stretch[n]) / len(stretch[n])
            for n, r in by_node.items()}


def run_seam(seam, work, msh, steps, tolerance, linear):
    yaml = os.path.join(work, "hertz_seam.yaml")
    open(yaml, "w").write(YAML.format(mesh=msh, steps=steps, tolerance=tolerance, linear=linear))
    out_dir = os.path.join(work, "seam_out_" + linear)
    stdout, wall, cpu = timed([seam, "run", yaml, "-o", out_dir, "--quiet"])
    steps_rows = read_csv(os.path.join(out_dir, "steps.csv"))
    summary = json.load(open(os.path.join(out_dir, "summary.json")))
    force = abs(ca.reaction(out_dir, "top", 2)) * 4
    rows = read_csv(os.path.join(out_dir, "interface_contact.csv"))  # the last step
    facets, _ = ca.slave_facets(ca.read_msh(msh), "surface")
    tractions = reference_tractions(rows, facets)
    p0, radius = ca.fitted_hertz(rows, 3, current=False, tractions=tractions)
    return {"code": "seam" if linear == "auto" else "seam:" + linear, "dofs": summary.get("dofs", 0) or 0,
            "newton": [int(r["newton_iterations"]) for r in steps_rows], "force": force,
            "radius": radius, "p0": p0, "active": sum(1 for r in rows if ca.is_active(r)),
            "wall": wall, "cpu": cpu, "own": summary["wall_seconds"]}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--seam", default=os.path.join(ROOT, "build", "bin", "seam"))
    ap.add_argument("--python", default="/usr/bin/python3", help="a Python with getfem")
    ap.add_argument("--refine", default="1.65")
    ap.add_argument("--steps", type=int, default=1)
    # GetFEM's Newton did not reach 1e-10 on 21,861 and 73,977 dofs in 50 iterations.
    ap.add_argument("--tolerance", type=float, default=1e-8)
    ap.add_argument("--linear", default="auto", choices=["auto", "direct", "iterative"])
    ap.add_argument("--r", type=float, default=10.0, help="GetFEM's augmentation parameter")
    # seam:direct, seam:iterative run seam with that `solver.linear` (seam alone: --linear).
    ap.add_argument("--codes", nargs="+", default=["getfem", "seam"])
    a = ap.parse_args()
    work = tempfile.mkdtemp(prefix="peers_getfem_")
    m22, m41 = mesh(work, a.refine)
    results = []
    for code in a.codes:
        if code == "getfem":
            results.append(run_getfem(a.python, m22, a.steps, a.tolerance, a.r))
        elif code in ("seam", "seam:auto", "seam:direct", "seam:iterative"):
            linear = code.split(":")[1] if ":" in code else a.linear
            results.append(run_seam(a.seam, work, m41, a.steps, a.tolerance, linear))
        else:
            sys.exit("unknown code %r (getfem, seam, seam:direct, seam:iterative)" % code)
        print(json.dumps(results[-1]), flush=True)
    print("\nrefine %s, %d load step(s), relative tolerance %g (work directory %s)"
          % (a.refine, a.steps, a.tolerance, work))
    print("%-14s %7s %-12s %7s %11s %9s %8s %9s %8s %9s" % (
        "code", "dofs", "Newton", "active", "F", "a", "a err", "p0", "p0 err", "wall [s]") + "  own [s]  CPU [s]")
    for r in results:
        a_h, p0_h = ca.hertz_3d(r["force"], R, ESTAR)
        print("%-14s %7d %-12s %7d %11.6g %9.6f %+7.2f%% %9.6f %+7.2f%% %9.2f" % (
            r["code"], r["dofs"], "+".join(str(n) for n in r["newton"]), r["active"],
            r["force"], r["radius"], 100 * (r["radius"] - a_h) / a_h, r["p0"],
            100 * (r["p0"] - p0_h) / p0_h, r["wall"]) + "  %7.2f  %7.2f" % (r["own"], r["cpu"]))
    g = next((r for r in results if r["code"] == "getfem"), None)
    for s in results:
        if g is not None and s is not g:
            print("%s / GetFEM: wall time %.3f, CPU time %.3f; load F: seam / GetFEM - 1 = %+.3f %%"
                  % (s["code"], s["wall"] / g["wall"], s["cpu"] / g["cpu"],
                     100 * (s["force"] / g["force"] - 1)))


if __name__ == "__main__":
    main()
