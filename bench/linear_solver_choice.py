#!/usr/bin/env python3
"""Where `solver.linear: auto` switches from MUMPS to GMRES + GAMG: a hex8 cube (Neo-Hooke,
E = 200, nu = 0.3) clamped at the bottom and pressed by a tilted rigid plane (frictionless
contact, dual multipliers condensed) in two load steps, solved with `linear: direct` and
`linear: iterative` at growing n^3 meshes.

Printed per mesh and solver: dofs, Newton iterations, CPU seconds of the whole run (user +
sys; assembly and contact are the same for both, so the difference is the linear solver's),
the solver's share from summary.json (linear_solve wall seconds) and the peak RSS; then the
ratio iterative / direct. OpenBLAS and OpenMP run single-threaded so that CPU time is not
inflated by spinning threads on a shared machine.

Usage: /usr/bin/python3 bench/linear_solver_choice.py [--seam build/bin/seam]
       [--divisions 6 10 14 18]
"""
import argparse
import csv
import json
import os
import shutil
import subprocess
import tempfile

GEO = """n = %d;
Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {1, 1, 0}; Point(4) = {0, 1, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = n + 1; Transfinite Surface{1}; Recombine Surface{1};
out[] = Extrude {0, 0, 1} { Surface{1}; Layers{n}; Recombine; };
Physical Volume("cube") = {out[1]};
Physical Surface("bottom") = {1};
Physical Surface("top") = {out[0]};
"""

YAML = """dimension: 3
mesh: {geo: cube.geo}
materials:
  m: {model: neo_hooke, young: 200, poisson: 0.3}
bodies:
  - {region: cube, material: m}
boundary_conditions:
  - {region: bottom, type: dirichlet, value: [0, 0, 0]}
interfaces:
  - name: press
    type: contact
    slave: top
    rigid_plane: {point: [0, 0, 1.0], normal: [0.3, 0.2, -1], motion: ["0", "0", "-0.05*t"]}
time: {integrator: static, end: 1, steps: 2}
solver:
  linear: %s
"""


def run(seam, n, linear):
    folder = tempfile.mkdtemp(prefix="seam_bench_linear_")
    with open(os.path.join(folder, "cube.geo"), "w") as f:
        f.write(GEO % n)
    with open(os.path.join(folder, "cube.yaml"), "w") as f:
        f.write(YAML % linear)
    env = dict(os.environ, OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    before = os.times()
    subprocess.run(["/usr/bin/time", "-f", "%M", "-o", os.path.join(folder, "rss"), seam, "run",
                    "cube.yaml", "-o", "out", "--quiet"], cwd=folder, env=env, check=True)
    after = os.times()
    cpu = (after.children_user - before.children_user) + (after.children_system
                                                         - before.children_system)
    with open(os.path.join(folder, "out", "summary.json")) as f:
        summary = json.load(f)
    with open(os.path.join(folder, "out", "steps.csv")) as f:
        iterations = sum(int(r["newton_iterations"]) for r in csv.DictReader(f))
    with open(os.path.join(folder, "rss")) as f:
        rss = int(f.read().split()[-1]) / 1024.0
    shutil.rmtree(folder, ignore_errors=True)
    return summary["dofs"], iterations, cpu, summary["timings"]["linear_solve"], rss


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    here = os.path.dirname(os.path.abspath(__file__))
    parser.add_argument("--seam", default=os.path.join(here, "..", "build", "bin", "seam"))
    parser.add_argument("--divisions", type=int, nargs="+", default=[6, 10, 14, 18])
    args = parser.parse_args()
    print("%4s %8s %-10s %5s %9s %12s %9s" % ("n", "dofs", "linear", "its", "CPU s",
                                             "solve wall s", "RSS MB"))
    for n in args.divisions:
        result = {}
        for linear in ("direct", "iterative"):
            dofs, its, cpu, solve, rss = run(args.seam, n, linear)
            result[linear] = (cpu, rss)
            print("%4d %8d %-10s %5d %9.2f %12.2f %9.0f" % (n, dofs, linear, its, cpu, solve, rss))
        print("%4d %8d iterative/direct: CPU %.2f, RSS %.2f" % (
            n, dofs, result["iterative"][0] / result["direct"][0],
            result["iterative"][1] / result["direct"][1]))


if __name__ == "__main__":
    main()
