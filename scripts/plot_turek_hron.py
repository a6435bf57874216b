#!/usr/bin/env python3
"""Draws the tip displacement of the Turek-Hron flag (examples/turek_hron) against time, with
the published mean +- amplitude of the benchmark (Turek & Hron 2006, Table 8) as bands.

    build/bin/seam run examples/turek_hron/csm3.yaml -o csm3_out
    /usr/bin/python3 scripts/plot_turek_hron.py csm3_out -o csm3.png
"""
import argparse
import csv
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# CSM3: (mean, amplitude) of u_x(A) and u_y(A) in m.
REFERENCE = {"ux": (-14.305e-3, 14.305e-3), "uy": (-63.607e-3, 65.160e-3)}


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("output", help="the run's output directory (probes.csv, probe 0 = A)")
    parser.add_argument("-o", "--png", default="turek_hron.png")
    args = parser.parse_args()
    with open(os.path.join(args.output, "probes.csv")) as f:
        rows = [r for r in csv.DictReader(f) if int(r["probe"]) == 0]
    t = [float(r["time"]) for r in rows]
    fig, axes = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    for ax, key in zip(axes, ("ux", "uy")):
        ax.plot(t, [1e3 * float(r[key]) for r in rows], label="seam")
        mean, amplitude = REFERENCE[key]
        for value, style in ((mean, "--"), (mean - amplitude, ":"), (mean + amplitude, ":")):
            ax.axhline(1e3 * value, color="k", linestyle=style, linewidth=0.8)
        ax.set_ylabel("%s(A) [mm]" % key.replace("u", "u_"))
        ax.grid(alpha=0.3)
    axes[0].set_title("Turek-Hron CSM3: tip displacement (dashed: published mean, dotted: "
                      "mean +- amplitude)", fontsize=9)
    axes[1].set_xlabel("t [s]")
    fig.tight_layout()
    fig.savefig(args.png, dpi=120)
    print("wrote", args.png)


if __name__ == "__main__":
    main()
