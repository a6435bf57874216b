#!/usr/bin/env python3
"""DFG 2D-1 (Schaefer & Turek 1996, Re = 20) on the example's geometry (examples/dfg_cylinder)
under uniform refinement of its cell sizes (h, hc) = (0.08, 0.012) / 2^k, Taylor-Hood P2/P1:
the direct solver (MUMPS) against the iterative one (FGMRES + velocity | pressure Schur
fieldsplit, BoomerAMG on both blocks), the same with the pressure convection-diffusion Schur
block (`pcd`: `solver.linear: iterative` and `-fluid_schur pcd` after `--`), and what
`solver.linear: auto` picks. With --case 2d3:
the first 20 steps (dt = 0.04, generalized-alpha, up to t = 0.8) of DFG 2D-3 on the same
meshes, whose iterative solver has ILU(0) on the velocity block; c_D is the last step's
(no reference).

Printed: one row per level and solver: dofs, c_D and its relative error against 5.57954, the
CPU time (user + system) of the run and per Newton iteration (the run's CPU time over its linear
solves), the wall time of the run and per Newton iteration (set-up and meshing included), the
wall time per Newton iteration of seam's own assembly and linear solves (summary.json's
timings: without meshing and set-up), its
peak resident memory (for np > 1: the CPU time of all ranks, the largest rank's memory), the
1-minute load average of the machine when the run started (the machine is shared: wall times
mean little, CPU times are the measure), Newton's linear solves, the Krylov iterations per
Newton step, and the linear solver the run names in summary.json; after the iterative row of a
level, the ratio of its CPU time to the direct one's. The rule of `auto` for fluids
(src/seam/problem/linear_solver_choice.hpp) rests on these ratios.

With --variant 'label|options' (repeatable) every level and solver is run once per variant,
each with the variant's PETSc options added after -- (a NAME=value word sets the run's
environment instead, e.g. GLIBC_TUNABLES=glibc.malloc.hugetlb=1), interleaved level by level so that the
variants share the machine's load; --repeat N runs each N times. A last table gives, per solver
and variant, the smallest CPU time per Newton iteration over the repeats and its growth from
level to level against the dofs' (docs/fluid.md, "PCD's cost on the finest mesh").

Usage: /usr/bin/python3 bench/dfg_benchmark.py [--seam build/bin/seam] [--levels 0,1,2]
           [--solvers direct,iterative,pcd] [--np 1] [--case 2d1|2d3]
           [--variant 'label|-fieldsplit_u_pc_hypre_boomeramg_P_max 4']... [--repeat 1]
"""
import argparse
import json
import os
import shutil
import subprocess
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLE = os.path.join(HERE, "..", "examples", "dfg_cylinder")
CD_REF = 5.57954


def level_folder(level):
    """A new temporary folder holding the example's dfg.geo with the cell sizes
    (h, hc) = (0.08, 0.012) / 2^level."""
    folder = tempfile.mkdtemp(prefix="seam_bench_dfg_")
    with open(os.path.join(EXAMPLE, "dfg.geo")) as f:
        geo = f.read()
    geo = geo.replace("DefineNumber[0.04,", "DefineNumber[%g," % (0.08 / 2 ** level))
    geo = geo.replace("DefineNumber[0.006,", "DefineNumber[%g," % (0.012 / 2 ** level))
    with open(os.path.join(folder, "dfg.geo"), "w") as f:
        f.write(geo)
    return folder


def run(seam, np, level, solver, case, options=()):
    if solver == "pcd":
        solver, options = "iterative", ["-fluid_schur", "pcd"] + list(options)
    folder = level_folder(level)
    with open(os.path.join(EXAMPLE, "dfg_%s.yaml" % case)) as f:
        yaml = f.read() + "solver: {linear: %s}\n" % solver
    if case == "2d3":
        yaml = yaml.replace("geo: dfg_2d3.geo", "geo: dfg.geo").replace("end: 8", "end: 0.8")
        yaml = yaml.replace("dt: 0.01", "dt: 0.04").replace("every: 10", "every: 100000")
    with open(os.path.join(folder, "case.yaml"), "w") as f:
        f.write(yaml)
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    # NAME=value words among the options set the run's environment instead.
    env.update(o.split("=", 1) for o in options if "=" in o and not o.startswith("-"))
    options = [o for o in options if "=" not in o or o.startswith("-")]
    out = os.path.join(folder, "out")
    cmd = [seam, "run", os.path.join(folder, "case.yaml"), "-o", out, "--quiet"]
    if options:
        cmd += ["--"] + list(options)
    if np > 1:
        cmd = ["mpirun", "--oversubscribe", "-np", str(np)] + cmd
    load = os.getloadavg()[0]
    start = time.monotonic()
    proc = subprocess.Popen(cmd, env=env)
    # The rusage of the run and of its waited-for descendants (the ranks under mpirun).
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.monotonic() - start
    proc.returncode = os.waitstatus_to_exitcode(status)
    if proc.returncode != 0:
        raise SystemExit("%s failed with exit code %d (case in %s)"
                         % (" ".join(cmd), proc.returncode, folder))
    with open(os.path.join(out, "summary.json")) as f:
        info = json.load(f)
    shutil.rmtree(folder)
    fx = info["forces"][0]["fx"]
    solves = info["linear_solves"]
    u_mean = 0.2 if case == "2d1" else 1.0
    return {"dofs": info["dofs"], "cd": 2 * fx / (1.0 * u_mean ** 2 * 0.1),
            "cpu": usage.ru_utime + usage.ru_stime, "wall": wall,
            "newton_wall": sum(info["timings"].get(k, 0.0) for k in ("assembly", "linear_solve")),
            "rss": usage.ru_maxrss / 1024.0,
            "load": load, "solves": solves, "krylov": info["linear_iterations"] / solves,
            "solver": info.get("linear_solver", "?")}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--seam", default=os.path.join(HERE, "..", "build", "bin", "seam"))
    parser.add_argument("--levels", default="0,1,2",
                        help="comma-separated refinement levels k: (h, hc) = (0.08, 0.012) / 2^k")
    parser.add_argument("--solvers", default="direct,iterative",
                        help="comma-separated values of solver.linear (direct, iterative, auto) "
                        "or pcd (iterative with -fluid_schur pcd)")
    parser.add_argument("--np", type=int, default=1)
    parser.add_argument("--case", choices=("2d1", "2d3"), default="2d1")
    parser.add_argument("--options", default="",
                        help="PETSc options passed after -- to every run, e.g. "
                        "'-pc_fieldsplit_schur_precondition selfp'")
    parser.add_argument("--variant", action="append", default=[],
                        help="'label|PETSc options' added to --options; repeatable")
    parser.add_argument("--repeat", type=int, default=1)
    args = parser.parse_args()
    variants = [(v.split("|", 1)[0], v.split("|", 1)[1].split() if "|" in v else [])
                for v in args.variant] or [("", [])]
    levels = [int(k) for k in args.levels.split(",")]
    solvers = args.solvers.split(",")
    if args.case == "2d1":
        print("DFG 2D-1, Taylor-Hood P2/P1, np = %d, c_D reference %.5f" % (args.np, CD_REF))
    else:
        print("DFG 2D-3, 20 steps of dt = 0.04, Taylor-Hood P2/P1, np = %d" % args.np)
    print("%5s %8s %-9s %9s %9s %9s %8s %8s %9s %9s %8s %5s %6s %7s  %s" % (
        "level", "dofs", "linear", "c_D", "error", "CPU [s]", "CPU/newt", "wall [s]", "wall/newt",
        "solve/newt", "RSS [MB]", "load", "newton", "krylov", "linear solver of the run"))
    best = {}
    for level in levels:
        cpu = {}
        for _, solver, (label, extra) in ((i, s, v) for i in range(args.repeat)
                                          for s in solvers for v in variants):
            r = run(args.seam, args.np, level, solver, args.case, args.options.split() + extra)
            cpu[solver] = r["cpu"]
            key = (solver, label)
            per_newton = r["cpu"] / r["solves"]
            old = best.setdefault(key, {}).get(level)
            if old is None or per_newton < old[1]:
                best[key][level] = (r["dofs"], per_newton,
                                    None if r["solver"].startswith("direct") else r["krylov"])
            if label:
                print("      variant: %s" % label)
            direct = r["solver"].startswith("direct")
            error = "%+8.4f%%" % (100 * (r["cd"] / CD_REF - 1)) if args.case == "2d1" else "-"
            row = "%5d %8d %-9s %9.6f %9s %9.2f %8.3f %8.2f %9.3f %10.3f %8.0f %5.2f %6d %7s  %s"
            print(row % (
                level, r["dofs"], solver, r["cd"], error, r["cpu"], r["cpu"] / r["solves"],
                r["wall"], r["wall"] / r["solves"], r["newton_wall"] / r["solves"], r["rss"],
                r["load"], r["solves"],
                "-" if direct else "%.1f" % r["krylov"],
                r["solver"]), flush=True)
        for solver in ("iterative", "pcd"):
            if "direct" in cpu and solver in cpu and len(variants) == 1:
                print("%5d %8s %s / direct CPU time: %.2f" % (
                    level, "", solver, cpu[solver] / cpu["direct"]), flush=True)
    print("\nCPU per Newton iteration, the smallest of %d run(s), and its growth against the "
          "dofs' from the level before" % args.repeat)
    for (solver, label), rows in best.items():
        print("%s %s" % (solver, label))
        previous = None
        for level in levels:
            dofs, t, krylov = rows[level]
            growth = "" if previous is None else "x%.2f for x%.2f dofs" % (
                t / previous[1], dofs / previous[0])
            print("  %8d dofs %9.3f s %7s Krylov/Newton  %s" % (
                dofs, t, "-" if krylov is None else "%.1f" % krylov, growth))
            previous = (dofs, t)
        first, last = rows[levels[0]], rows[levels[-1]]
        print("  over the range: x%.1f for x%.1f dofs" % (last[1] / first[1], last[0] / first[0]))


if __name__ == "__main__":
    main()
