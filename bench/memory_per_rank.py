#!/usr/bin/env python3
"""Peak memory per rank of a tied 3D problem (examples/tied_blocks refined: hexahedra below,
tetrahedra above, non-matching at z = 1, dual mortar condensed), solved with the iterative
solver (GMRES + GAMG) at np = 1, 2, 4, from summary.json ranks_detail (peak_rss_mb).

The mesh is written once by the gmsh executable (binary MSH 4.1) and read from that file by
both readers: "chunked" (every rank reads its share, PT-Scotch partitions in parallel; no rank
holds the whole mesh) and "rank0" (SEAM_MESH_READER=rank0: rank 0 reads the whole mesh
through the Gmsh API, partitions with METIS and sends the parts).

Printed: reader, dofs, per-rank peak RSS (max and min over the ranks), the ratio of the largest
rank to the same reader's np = 1 run, the cells each rank assembles and holds, the Newton
iterations, the whole run's user + system CPU and wall (s; /usr/bin/time -v around mpirun) and
both per Newton iteration, and the largest resident set of any one process /usr/bin/time saw
("time MB"); then the largest rank's cpu_timings. Then, per
phase of the run (summary.json ranks_detail memory_phases: the peak between the previous phase
mark and this one, and the resident set at the mark), the largest rank's figures at each np.

The constant per-process base (MPI, PETSc, libraries, the code itself) is measured by the same
case at 2 divisions (a few hundred dofs): "- base" ratios subtract it from both runs,
(max_np - base_np) / (max_1 - base_1), i.e. what falls with the problem size.

Usage: /usr/bin/python3 bench/memory_per_rank.py [--seam build/bin/seam] [--divisions 30]
       [--size 0.04] [--ranks 1 2 4] [--readers chunked rank0] [--no-base]
       [--material linear_elastic]
The 2e6-dof case of docs/parallel.md: --divisions 85 --size 0.026 --readers chunked
--material linear_elastic.
"""
import argparse
import csv
import json
import os
import re
import shutil
import subprocess
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLE = os.path.join(HERE, "..", "examples", "tied_blocks")


def time_v(stderr):
    """Max RSS (MB), user + system CPU (s) and wall (s) from /usr/bin/time -v."""
    def field(name):
        return re.search(re.escape(name) + r":\s*(\S+)", stderr).group(1)
    wall = 0.0
    for part in field("Elapsed (wall clock) time (h:mm:ss or m:ss)").split(":"):
        wall = 60 * wall + float(part)
    return (float(field("Maximum resident set size (kbytes)")) / 1024,
            float(field("User time (seconds)")) + float(field("System time (seconds)")), wall)


def make_case(divisions, size, material):
    """A folder with blocks.msh (gmsh, binary MSH 4.1) and blocks.yaml reading it."""
    folder = tempfile.mkdtemp(prefix="seam_bench_mem_")
    for f in ("blocks.yaml", "blocks.geo"):
        shutil.copy(os.path.join(EXAMPLE, f), folder)
    geo = os.path.join(folder, "blocks.geo")
    with open(geo) as f:
        text = f.read()
    text = text.replace("Transfinite Curve{1:12} = 6;", "Transfinite Curve{1:12} = %d;"
                        % (divisions + 1)).replace("= 0.15;", "= %g;" % size)
    with open(geo, "w") as f:
        f.write(text)
    subprocess.run(["gmsh", "-3", "-bin", "-format", "msh41", geo, "-o",
                    os.path.join(folder, "blocks.msh")], check=True, capture_output=True)
    yaml = os.path.join(folder, "blocks.yaml")
    with open(yaml) as f:
        text = f.read().replace("steps: 5}", "steps: 1}\nsolver: {linear: iterative}")
        text = text.replace("geo: blocks.geo", "file: blocks.msh")
        text = text.replace("model: neo_hooke", "model: " + material)
    with open(yaml, "w") as f:
        f.write(text)
    return folder


def run(seam, np, folder, reader):
    """summary.json of one run, with what /usr/bin/time -v saw ("time": max RSS of any one
    process in MB, user + system CPU of all ranks, wall) and the Newton iterations."""
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               SEAM_MESH_READER=reader)
    out = os.path.join(folder, "out")
    shutil.rmtree(out, ignore_errors=True)
    p = subprocess.run(["/usr/bin/time", "-v", "mpirun", "--oversubscribe", "-np", str(np), "-x",
                        "SEAM_MESH_READER", seam, "run", os.path.join(folder, "blocks.yaml"),
                        "-o", out, "--quiet"], env=env, capture_output=True, text=True)
    if p.returncode != 0:
        raise SystemExit("np %d failed (%d):\n%s\n%s" % (np, p.returncode, p.stdout[-3000:],
                                                         p.stderr[-3000:]))
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    with open(os.path.join(out, "steps.csv")) as f:
        summary["newton"] = sum(int(r["newton_iterations"]) for r in csv.DictReader(f))
    summary["time"] = time_v(p.stderr)
    return summary


def phase_table(runs):
    """Per phase, the largest rank's peak and current RSS (MB) of each run."""
    names = [p["phase"] for p in runs[0][1]["ranks_detail"][0].get("memory_phases", [])]
    if not names:
        return
    print("\nper phase, largest rank: peak MB since the previous phase / resident MB at its end")
    print("%-22s" % "phase" + "".join("%22s" % ("np %d" % np) for np, _ in runs))
    for k, name in enumerate(names):
        row = "%-22s" % name
        for _, s in runs:
            phases = [r["memory_phases"][k] for r in s["ranks_detail"]]
            row += "%13.1f /%7.1f" % (max(p["peak_mb"] for p in phases),
                                      max(p["rss_mb"] for p in phases))
        print(row)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--seam", default=os.path.join(HERE, "..", "build", "bin", "seam"))
    parser.add_argument("--divisions", type=int, default=30)
    parser.add_argument("--size", type=float, default=0.04)
    parser.add_argument("--ranks", type=int, nargs="+", default=[1, 2, 4])
    parser.add_argument("--readers", nargs="+", default=["chunked", "rank0"])
    parser.add_argument("--material", default="neo_hooke",
                        help="the blocks' model (neo_hooke as the example; linear_elastic: "
                        "one Newton iteration, the same matrices and peak)")
    parser.add_argument("--results", default="",
                        help="JSON file keeping every run's summary: a run found there is not "
                        "repeated (run the large cases one np at a time, then print them all)")
    parser.add_argument("--no-base", action="store_true",
                        help="do not measure the per-process base (the tiny case)")
    args = parser.parse_args()
    seam = os.path.abspath(args.seam)
    stored = {}
    if args.results and os.path.exists(args.results):
        with open(args.results) as f:
            stored = json.load(f)
    cases = {}

    def measured(np, divisions, size, reader):
        key = "%s np %d divisions %d size %g %s" % (reader, np, divisions, size, args.material)
        if key not in stored:
            if (divisions, size) not in cases:
                cases[(divisions, size)] = make_case(divisions, size, args.material)
            stored[key] = run(seam, np, cases[(divisions, size)], reader)
            if args.results:
                with open(args.results, "w") as f:
                    json.dump(stored, f)
        return stored[key]

    base_rss = {}
    if not args.no_base:
        for np in args.ranks:
            s = measured(np, 2, 0.5, args.readers[0])
            base_rss[np] = max(r["peak_rss_mb"] for r in s["ranks_detail"])
        print("base (2 divisions, %d dofs): largest rank %s MB" % (
            s["dofs"], ", ".join("np %d %.1f" % (np, base_rss[np]) for np in args.ranks)))
    print("%8s %3s %9s %10s %10s %9s %7s %17s %6s %8s %8s %8s %8s %8s" % (
        "reader", "np", "dofs", "max RSS MB", "min RSS MB", "max/np=1", "- base",
        "cells own/held", "newton", "CPU s", "wall s", "CPU/it", "wall/it", "time MB"))
    for reader in args.readers:
        runs = []
        for np in args.ranks:
            s = measured(np, args.divisions, args.size, reader)
            runs.append((np, s))
            rss = [r["peak_rss_mb"] for r in s["ranks_detail"]]
            one = max(r["peak_rss_mb"] for r in runs[0][1]["ranks_detail"])
            net = float("nan")
            if base_rss:
                net = (max(rss) - base_rss[np]) / (one - base_rss[runs[0][0]])
            own = max(r["cells"] for r in s["ranks_detail"])
            held = max(r["cells"] + r["ghost_cells"] for r in s["ranks_detail"])
            time_rss, cpu, wall = s["time"]
            it = max(s["newton"], 1)
            print("%8s %3d %9d %10.1f %10.1f %9.3f %7.3f %9d/%-7d %6d %8.1f %8.1f %8.1f %8.1f "
                  "%8.1f" % (reader, np, s["dofs"], max(rss), min(rss), max(rss) / one, net,
                             own, held, s["newton"], cpu, wall, cpu / it, wall / it, time_rss),
                  flush=True)
            # What each rank holds for the interfaces: cells held only for an interface side,
            # slave facets it integrates, master facets ghosted to it.
            print("%8s %3s interface per rank: cells %s, slave facets %s, master ghosts %s" % (
                "", "", [r["interface_cells"] for r in s["ranks_detail"]],
                [r["slave_elements"] for r in s["ranks_detail"]],
                [r["master_ghosts"] for r in s["ranks_detail"]]), flush=True)
            print("%8s %3s largest rank's CPU s: %s; seam's wall %.1f s" % (
                "", "", ", ".join("%s %.1f" % kv for kv in s["cpu_timings"].items()),
                s["wall_seconds"]), flush=True)
        phase_table(runs)
    for folder in cases.values():
        shutil.rmtree(folder, ignore_errors=True)


if __name__ == "__main__":
    main()
