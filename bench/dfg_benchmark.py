#!/usr/bin/env python3
"""DFG 2D-1 (Schaefer & Turek 1996, Re = 20) on the example's geometry (examples/dfg_cylinder)
under uniform refinement of its cell sizes (h, hc) = (0.08, 0.012) / 2^k, Taylor-Hood P2/P1:
the error of c_D against the reference 5.57954 with the number of dofs and the wall time, for
the direct solver (MUMPS) and the iterative one (GMRES + velocity | pressure Schur fieldsplit),
and the time per Newton iteration (assembly + linear solve, from summary.json timings over
its linear_solves) against the dofs.

Printed: one row per level and solver: dofs, c_D, its relative error, wall seconds, Newton
iterations, GMRES iterations per solve, seconds per Newton iteration and that time per dof
(constant for a solver that scales linearly).

Usage: /usr/bin/python3 bench/dfg_benchmark.py [--seam build/bin/seam] [--levels 3] [--np 1]
"""
import argparse
import json
import os
import shutil
import subprocess
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLE = os.path.join(HERE, "..", "examples", "dfg_cylinder")
CD_REF = 5.57954


def run(seam, np, level, solver):
    folder = tempfile.mkdtemp(prefix="seam_bench_dfg_")
    with open(os.path.join(EXAMPLE, "dfg.geo")) as f:
        geo = f.read()
    geo = geo.replace("DefineNumber[0.04,", "DefineNumber[%g," % (0.08 / 2 ** level))
    geo = geo.replace("DefineNumber[0.006,", "DefineNumber[%g," % (0.012 / 2 ** level))
    with open(os.path.join(folder, "dfg.geo"), "w") as f:
        f.write(geo)
    with open(os.path.join(EXAMPLE, "dfg_2d1.yaml")) as f:
        yaml = f.read() + "solver: {linear: %s}\n" % solver
    with open(os.path.join(folder, "case.yaml"), "w") as f:
        f.write(yaml)
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    out = os.path.join(folder, "out")
    cmd = [seam, "run", os.path.join(folder, "case.yaml"), "-o", out, "--quiet"]
    if np > 1:
        cmd = ["mpirun", "--oversubscribe", "-np", str(np)] + cmd
    subprocess.run(cmd, check=True, env=env)
    with open(os.path.join(out, "summary.json")) as f:
        info = json.load(f)
    shutil.rmtree(folder)
    fx = info["forces"][0]["fx"]
    cd = 2 * fx / (1.0 * 0.2 ** 2 * 0.1)
    t = info["timings"]
    solves = info["linear_solves"]
    return {"dofs": info["dofs"], "cd": cd, "wall": info["wall_seconds"], "solves": solves,
            "gmres": info["linear_iterations"] / solves,
            "per_newton": (t["assembly"] + t["linear_solve"]) / solves}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--seam", default=os.path.join(HERE, "..", "build", "bin", "seam"))
    parser.add_argument("--levels", type=int, default=3)
    parser.add_argument("--np", type=int, default=1)
    args = parser.parse_args()
    print("DFG 2D-1, Taylor-Hood P2/P1, np = %d, c_D reference %.5f" % (args.np, CD_REF))
    print("%5s %9s %-9s %10s %10s %9s %6s %7s %12s %14s" % (
        "level", "dofs", "solver", "c_D", "error", "wall [s]", "newton", "gmres",
        "s/newton it", "us/(it * dof)"))
    for level in range(args.levels):
        for solver in ("direct", "iterative"):
            r = run(args.seam, args.np, level, solver)
            print("%5d %9d %-9s %10.6f %+9.4f%% %9.2f %6d %7s %12.4f %14.3f" % (
                level, r["dofs"], solver, r["cd"], 100 * (r["cd"] / CD_REF - 1), r["wall"],
                r["solves"], "%.0f" % r["gmres"] if solver == "iterative" else "-",
                r["per_newton"], 1e6 * r["per_newton"] / r["dofs"]), flush=True)


if __name__ == "__main__":
    main()
