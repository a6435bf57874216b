#!/usr/bin/env python3
"""Runs DFG 2D-1 (examples/dfg_cylinder/dfg_2d1.yaml, Re = 20, steady) on the example's geometry
with the cell sizes (h, hc) = (0.08, 0.012) / 2^k for the levels given, and draws the relative
errors of c_D, c_L and the pressure difference against the dofs (log-log), with the
benchmark's reference values (John & Matthies 2001) and issue 14's tolerances; prints the table.

    /usr/bin/python3 scripts/plot_dfg_2d1.py [--seam build/bin/seam] [--levels 0,1,2,3]
        [-o examples/dfg_cylinder/dfg_2d1.png]

c = 2 F / (rho U_mean^2 D) = 500 F (U_mean = 0.2, D = 0.1, rho = 1), F the force of the group
`cylinder` in forces.csv; dp = p(0.15, 0.2) - p(0.25, 0.2) from probes.csv.
"""
import argparse
import csv
import json
import os
import shutil
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "bench"))
import dfg_benchmark  # noqa: E402  (the meshes of the benchmark's levels)

EXAMPLE = os.path.join(HERE, "..", "examples", "dfg_cylinder")
REFERENCE = {"c_D": 5.57954, "c_L": 0.010619, "dp": 0.11752}
TOLERANCE = {"c_D": 5e-3, "c_L": 5e-2, "dp": 5e-3}


def rows(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def run(seam, level):
    work = dfg_benchmark.level_folder(level)
    shutil.copy(os.path.join(EXAMPLE, "dfg_2d1.yaml"), os.path.join(work, "case.yaml"))
    out = os.path.join(work, "out")
    subprocess.run([seam, "run", os.path.join(work, "case.yaml"), "-o", out, "--quiet"],
                   check=True)
    force = [r for r in rows(os.path.join(out, "forces.csv")) if r["name"] == "cylinder"][-1]
    probes = rows(os.path.join(out, "probes.csv"))
    last = [r for r in probes if r["step"] == probes[-1]["step"]]
    with open(os.path.join(out, "summary.json")) as f:
        dofs = json.load(f)["dofs"]
    shutil.rmtree(work)
    return {"dofs": dofs, "c_D": 500 * float(force["fx"]), "c_L": 500 * float(force["fy"]),
            "dp": float(last[0]["pressure"]) - float(last[1]["pressure"])}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--seam", default=os.path.join(HERE, "..", "build", "bin", "seam"))
    ap.add_argument("--levels", default="0,1,2,3")
    ap.add_argument("-o", "--output", default=os.path.join(EXAMPLE, "dfg_2d1.png"))
    a = ap.parse_args()
    results = [run(os.path.abspath(a.seam), int(k)) for k in a.levels.split(",")]
    print("%10s %12s %10s %12s %10s %10s %10s" % ("dofs", "c_D", "error", "c_L", "error", "dp",
                                                  "error"))
    for r in results:
        print("%10d" % r["dofs"] + "".join(
            " %12.6f %+9.4f%%" % (r[q], 100 * (r[q] / REFERENCE[q] - 1)) for q in REFERENCE))
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    dofs = [r["dofs"] for r in results]
    for (q, label), colour in zip((("c_D", "$c_D$"), ("c_L", "$c_L$"), ("dp", r"$\Delta p$")),
                                  ("C0", "C1", "C2")):
        errors = [abs(r[q] / REFERENCE[q] - 1) for r in results]
        ax.loglog(dofs, errors, "o-", color=colour, label=label + " (ref. %g)" % REFERENCE[q])
        ax.axhline(TOLERANCE[q], color=colour, ls=":", lw=1)
    ax.set_xlabel("dofs (Taylor-Hood P2/P1)")
    ax.set_ylabel("relative error against the reference")
    ax.set_title("DFG 2D-1, Re = 20: errors under refinement (dotted: tolerances)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(a.output, dpi=120)
    print("wrote", a.output)


if __name__ == "__main__":
    main()
