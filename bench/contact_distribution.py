#!/usr/bin/env python3
"""The seed paper's Fig. 4/5 analogue on a whole seam run: a Hertz sphere pressed onto an
elastic block (examples/hertz_3d/sphere_block.yaml, two-body mortar contact), solved at
np = 1 .. N with the slave elements distributed with the bulk (`interface_distribution: bulk`)
and on their own (`independent`, rebalanced after every step whose max/min exceeds 1.2).

Printed per np and distribution, at the last step (from summary.json ranks_detail and
parallel.csv): integration cells and candidate pairs per rank as max/mean, the ranks that
have any, the redistributions made, the mortar phase time (evaluation + linearization,
max over ranks) with the wall time, and the master facets each rank received at the last
search (ghosted to it by bounding boxes) of the master surface's. On a machine with C cores, times are meaningful only at
np <= C; the counts are deterministic at any np.

Usage: /usr/bin/python3 bench/contact_distribution.py [--seam build/bin/seam] [--max-np 8]
       [--refine 1.5]
"""
import argparse
import csv
import json
import os
import shutil
import subprocess
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLE = os.path.join(HERE, "..", "examples", "hertz_3d")


def run(seam, np, distribution, refine, work):
    folder = tempfile.mkdtemp(prefix="seam_bench_dist_")
    for f in ("sphere_block.yaml", "sphere_block.geo"):
        shutil.copy(os.path.join(EXAMPLE, f), folder)
    geo = os.path.join(folder, "sphere_block.geo")
    with open(geo) as f:
        text = f.read().replace("refine = 1;", "refine = %g;" % refine)
    with open(geo, "w") as f:
        f.write(text)
    yaml = os.path.join(folder, "sphere_block.yaml")
    with open(yaml) as f:
        text = f.read().replace(
            "solver:", "parallel: {interface_distribution: %s, work: %s}\nsolver:"
            % (distribution, work))
    with open(yaml, "w") as f:
        f.write(text)
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_rmaps_base_oversubscribe="1")
    out = os.path.join(folder, "out")
    subprocess.run(["mpirun", "--oversubscribe", "-np", str(np), seam, "run", yaml, "-o", out,
                    "--quiet"], check=True, env=env)
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    with open(os.path.join(out, "parallel.csv")) as f:
        rows = list(csv.DictReader(f))
    shutil.rmtree(folder, ignore_errors=True)
    return summary, rows


def max_over_mean(values):
    mean = sum(values) / len(values)
    return max(values) / mean if mean > 0 else 1.0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--seam", default=os.path.join(HERE, "..", "build", "bin", "seam"))
    parser.add_argument("--max-np", type=int, default=8)
    parser.add_argument("--refine", type=float, default=1.0)
    parser.add_argument("--work", default="integration_cells", choices=["time", "integration_cells"])
    args = parser.parse_args()
    print("Hertz sphere on a block, refine %g, balance measure %s" % (args.refine, args.work))
    print("%3s %-12s %6s %12s %12s %8s %6s %10s %8s" % (
        "np", "distribution", "dofs", "cells max/mn", "pairs max/mn", "ranks>0", "moves",
        "mortar s", "wall s") + "  master facets received per rank")
    for np in range(1, args.max_np + 1):
        for distribution in ("bulk", "independent"):
            if np == 1 and distribution == "independent":
                continue
            summary, rows = run(args.seam, np, distribution, args.refine, args.work)
            detail = summary["ranks_detail"]
            cells = [r["integration_cells"] for r in detail]
            pairs = [r["pairs"] for r in detail]
            moves = sum(int(float(r["redistributed"])) for r in rows)
            received = "/".join(str(r["contact_master_received"]) for r in detail)
            print("%3d %-12s %6d %12.2f %12.2f %5d/%-2d %6d %10.3f %8.2f  %s of %d" % (
                np, distribution if np > 1 else "-", summary["dofs"], max_over_mean(cells),
                max_over_mean(pairs), sum(1 for c in cells if c > 0), np, moves,
                summary["timings"]["mortar"], summary["wall_seconds"], received,
                detail[0]["contact_master_facets"]))


if __name__ == "__main__":
    main()
