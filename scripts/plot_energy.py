#!/usr/bin/env python3
"""Draws the seed paper's Fig. 9 from seam runs: linear momentum, angular momentum and
energies over time, for one or more output directories (e.g. energy-momentum beside
generalized-alpha).

    /usr/bin/python3 scripts/plot_energy.py l_block_out l_block_ga_out -o fig9.png
"""
import argparse
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(directory):
    path = os.path.join(directory, "steps.csv")
    with open(path) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit("%s has no steps" % path)
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("runs", nargs="+", help="seam output directories")
    parser.add_argument("-o", "--output", default="energy_momentum.png")
    parser.add_argument("--free-from", type=float, default=0.5,
                        help="time after which no load acts (drift panel), default 0.5")
    args = parser.parse_args()
    fig, axes = plt.subplots(1, 4, figsize=(20, 4.2))
    for run in args.runs:
        d = read(run)
        label = os.path.basename(os.path.normpath(run))
        t = d["time"]
        p = [math.sqrt(x * x + y * y + z * z)
             for x, y, z in zip(d["momentum_x"], d["momentum_y"], d["momentum_z"])]
        L = [math.sqrt(x * x + y * y + z * z)
             for x, y, z in zip(d["angular_momentum_x"], d["angular_momentum_y"],
                                d["angular_momentum_z"])]
        axes[0].plot(t, p, label=label)
        axes[1].plot(t, L, label=label)
        axes[2].plot(t, d["total_energy"], label=label + " total")
        axes[2].plot(t, d["kinetic_energy"], "--", label=label + " kinetic")
        axes[2].plot(t, d["internal_energy"], ":", label=label + " internal")
        # Relative drift once the load is off, on a log scale: conservation made visible.
        free = [i for i, ti in enumerate(t) if ti > args.free_from + 1e-12]
        if free:
            i0 = free[0]
            for series, name in ((d["total_energy"], "energy"), (L, "|L|")):
                ref = abs(series[i0]) or 1.0
                axes[3].semilogy([t[i] for i in free],
                                 [max(abs(series[i] - series[i0]) / ref, 1e-17) for i in free],
                                 label="%s %s" % (label, name))
    axes[3].set_ylim(1e-17, 1)
    for ax, title in zip(axes, ("|linear momentum|", "|angular momentum|", "energy",
                                "relative drift after the load")):
        ax.set_xlabel("time")
        ax.set_title(title)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(args.output, dpi=120)
    print("wrote", args.output)


if __name__ == "__main__":
    main()
