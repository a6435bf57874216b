#!/usr/bin/env python3
"""Draws the drag and lift coefficients of a DFG cylinder run (examples/dfg_cylinder) against
time, with the reference peaks of DFG 2D-3 (John 2004), and prints the peaks and their errors.

    /usr/bin/python3 scripts/plot_fluid.py dfg_2d3_out -o dfg_2d3.png

c = 2 F / (rho U_mean^2 D) with --u-mean (default 1, DFG 2D-3), --diameter 0.1, --density 1;
the force is that of the force group --name (default cylinder) in forces.csv.
"""
import argparse
import csv
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

CD_MAX, T_CD, CL_MAX, T_CL = 2.95092, 3.93625, 0.47795, 5.69313


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("run", help="output directory of a seam run")
    ap.add_argument("-o", "--output", default="dfg.png")
    ap.add_argument("--name", default="cylinder")
    ap.add_argument("--u-mean", type=float, default=1.0)
    ap.add_argument("--diameter", type=float, default=0.1)
    ap.add_argument("--density", type=float, default=1.0)
    a = ap.parse_args()
    with open(os.path.join(a.run, "forces.csv")) as f:
        rows = [r for r in csv.DictReader(f) if r["name"] == a.name]
    scale = 2.0 / (a.density * a.u_mean ** 2 * a.diameter)
    t = [float(r["time"]) for r in rows]
    cd = [scale * float(r["fx"]) for r in rows]
    cl = [scale * float(r["fy"]) for r in rows]
    i, j = max(range(len(cd)), key=cd.__getitem__), max(range(len(cl)), key=cl.__getitem__)
    print("max c_D = %.5f at t = %.4f (reference %.5f at %.5f: %+.3f %%)"
          % (cd[i], t[i], CD_MAX, T_CD, 100 * (cd[i] / CD_MAX - 1)))
    print("max c_L = %.5f at t = %.4f (reference %.5f at %.5f: %+.3f %%)"
          % (cl[j], t[j], CL_MAX, T_CL, 100 * (cl[j] / CL_MAX - 1)))
    fig, ax = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    ax[0].plot(t, cd, label="seam")
    ax[0].plot([T_CD], [CD_MAX], "rx", label="reference peak (John 2004)")
    ax[0].set_ylabel("drag coefficient c_D")
    ax[1].plot(t, cl, label="seam")
    ax[1].plot([T_CL], [CL_MAX], "rx", label="reference peak (John 2004)")
    ax[1].set_ylabel("lift coefficient c_L")
    ax[1].set_xlabel("t")
    for x in ax:
        x.grid(True)
        x.legend()
    fig.tight_layout()
    fig.savefig(a.output, dpi=120)
    print("drawn in", a.output)


if __name__ == "__main__":
    main()
