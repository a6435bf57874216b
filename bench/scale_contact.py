#!/usr/bin/env python3
"""The largest 3D contact problem of the machine (issue 16): the unit cube of hex8 cells
indented by a rigid sphere, linear elastic, one load step (bench/peers/step42/compare.py's seam
input), at n cells per side (3 (n + 1)^3 dofs; n = 88 gives 2.1e6), on np ranks.

The mesh is written once per size by the gmsh executable (binary MSH 4.1) and read by the
chunked reader (`mesh.file`), so no rank holds the whole mesh. Every run is measured from
outside by `/usr/bin/time -v` around mpirun (maximum resident set of any one process, user and
system CPU of all ranks, wall) and from inside by summary.json (ranks_detail peak_rss_mb, the
timings and cpu_timings of the largest rank) and steps.csv (Newton iterations).

Printed per run: n, np, dofs, Newton iterations, peak RSS per rank (largest and smallest, MB),
the largest over the same n's first np, the whole run's user + system CPU and wall (s), both
per Newton iteration, the load step's wall (seam's own total), the largest rank's CPU seconds
of assembly, condensation and linear solve, the contact force and active nodes.

Usage: /usr/bin/python3 bench/scale_contact.py [--seam build/bin/seam] [--sizes 88]
       [--ranks 1 2] [--linear iterative] [--work DIR]
"""
import argparse
import csv
import json
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "peers", "step42"))
import compare  # noqa: E402  (the step-42 comparison's geometry and input)
import memory_per_rank  # noqa: E402  (time_v, phase_table)


def write_case(n, linear, folder):
    """cube.msh (gmsh, binary MSH 4.1; kept from an earlier run in the same folder) and
    cube.yaml reading it."""
    os.makedirs(folder, exist_ok=True)
    geo, msh = os.path.join(folder, "cube.geo"), os.path.join(folder, "cube.msh")
    if not os.path.exists(msh):
        with open(geo, "w") as f:
            f.write(compare.GEO.format(nodes=n + 1))
        subprocess.run(["gmsh", "-3", "-bin", "-format", "msh41", geo, "-o", msh + ".part"],
                       check=True, capture_output=True)
        os.rename(msh + ".part", msh)
    text = compare.YAML.format(n=n, linear="  linear: %s\n" % linear if linear else "")
    with open(os.path.join(folder, "cube.yaml"), "w") as f:
        f.write(text.replace("geo: cube.geo", "file: cube.msh"))


def run(seam, n, np, folder):
    out = os.path.join(folder, "out_np%d" % np)
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    p = subprocess.run(["/usr/bin/time", "-v", "mpirun", "--oversubscribe", "-np", str(np),
                        seam, "run", os.path.join(folder, "cube.yaml"), "-o", out, "--quiet"],
                       env=env, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit("n %d np %d failed (%d):\n%s\n%s" % (n, np, p.returncode, p.stdout[-3000:],
                                                     p.stderr[-3000:]))
    rss, cpu, wall = memory_per_rank.time_v(p.stderr)
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    with open(os.path.join(out, "steps.csv")) as f:
        steps = list(csv.DictReader(f))
    with open(os.path.join(out, "interfaces.csv")) as f:
        itf = list(csv.DictReader(f))[-1]
    return {
        "dofs": s["dofs"], "newton": sum(int(r["newton_iterations"]) for r in steps),
        "steps": len(steps), "rss": [r["peak_rss_mb"] for r in s["ranks_detail"]],
        "time_rss": rss, "cpu": cpu, "wall": wall, "own_wall": s["wall_seconds"],
        "tc": s["cpu_timings"], "force": float(itf["normal_force"]),
        "active": int(itf["active_nodes"]), "summary": s,
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--seam", default=os.path.join(HERE, "..", "build", "bin", "seam"))
    ap.add_argument("--sizes", type=int, nargs="+", default=[88])
    ap.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--linear", default="iterative", help="solver.linear ('' for the default)")
    ap.add_argument("--work", default="", help="directory for the runs (default: temporary, "
                    "removed at the end)")
    args = ap.parse_args()
    work = os.path.abspath(args.work or tempfile.mkdtemp(prefix="seam_scale_contact_"))
    seam = os.path.abspath(args.seam)
    print("%4s %3s %9s %6s %9s %9s %6s %9s %9s %9s %9s %9s %7s %7s %7s %10s %6s" % (
        "n", "np", "dofs", "newton", "max MB", "min MB", "/np1", "CPU s", "wall s",
        "CPU/it", "wall/it", "step s", "asm", "cond", "solve", "force", "active"))
    for n in args.sizes:
        folder = os.path.join(work, "n%d" % n)
        write_case(n, args.linear, folder)
        first, runs = None, []
        for np in args.ranks:
            r = run(seam, n, np, folder)
            runs.append((np, r["summary"]))
            first = first or max(r["rss"])
            it = max(r["newton"], 1)
            print("%4d %3d %9d %6d %9.1f %9.1f %6.3f %9.1f %9.1f %9.2f %9.2f %9.1f %7.1f %7.1f "
                  "%7.1f %10.4f %6d" % (
                      n, np, r["dofs"], r["newton"], max(r["rss"]), min(r["rss"]),
                      max(r["rss"]) / first, r["cpu"], r["wall"], r["cpu"] / it, r["wall"] / it,
                      r["own_wall"] / r["steps"], r["tc"]["assembly"], r["tc"]["condensation"],
                      r["tc"]["linear_solve"], r["force"], r["active"]), flush=True)
        memory_per_rank.phase_table(runs)
    if not args.work:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
