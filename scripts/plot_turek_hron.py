#!/usr/bin/env python3
"""Draws the tip displacement of the Turek-Hron flag (examples/turek_hron) against time, with
the published mean +- amplitude of the benchmark (Turek & Hron 2006, Tables 8 and 12) as bands:
CSM3 (u_x, u_y), with --fsi3 FSI3 and --fsi2 FSI2 (u_y and the lift on cylinder + flag), with
--cfd3 CFD3 (the
rigid flag: drag and lift on cylinder + flag).

    build/bin/seam run examples/turek_hron/csm3.yaml -o csm3_out
    /usr/bin/python3 scripts/plot_turek_hron.py csm3_out -o csm3.png
    /usr/bin/python3 scripts/plot_turek_hron.py fsi3_out --fsi3 -o fsi3.png
    /usr/bin/python3 scripts/plot_turek_hron.py fsi2_out --fsi2 -o fsi2.png
    /usr/bin/python3 scripts/plot_turek_hron.py cfd3_out --cfd3 -o cfd3.png
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from periodic_state import CFD3, FSI2, FSI3, histories  # noqa: E402

# CSM3: (mean, amplitude) of u_x(A) and u_y(A) in m.
REFERENCE = {"ux": (-14.305e-3, 14.305e-3), "uy": (-63.607e-3, 65.160e-3)}
UNITS = {"ux": ("u_x(A) [mm]", 1e3), "uy": ("u_y(A) [mm]", 1e3), "lift": ("lift [N/m]", 1.0),
         "drag": ("drag [N/m]", 1.0)}


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("output", help="the run's output directory (probes.csv, probe 0 = A)")
    parser.add_argument("-o", "--png", default="turek_hron.png")
    parser.add_argument("--fsi3", action="store_true", help="FSI3: u_y(A) and the lift")
    parser.add_argument("--fsi2", action="store_true", help="FSI2: u_y(A) and the lift")
    parser.add_argument("--cfd3", action="store_true", help="CFD3: drag and lift")
    parser.add_argument("--from", dest="start", type=float, default=0.0,
                        help="draw from this time on (default 0)")
    args = parser.parse_args()
    h = histories(args.output)
    fsi = FSI3 if args.fsi3 else FSI2 if args.fsi2 else None
    keys = ("uy", "lift") if fsi else ("drag", "lift") if args.cfd3 else ("ux", "uy")
    name = ("FSI3" if args.fsi3 else "FSI2" if args.fsi2 else "CFD3" if args.cfd3
            else "CSM3: tip displacement")
    fig, axes = plt.subplots(2, 1, figsize=(8, 6), sharex=True)
    for ax, key in zip(axes, keys):
        label, scale = UNITS[key]
        t, u = h[key]
        keep = [i for i, x in enumerate(t) if x >= args.start]
        ax.plot([t[i] for i in keep], [scale * u[i] for i in keep], label="seam")
        reference = fsi or (CFD3 if args.cfd3 else REFERENCE)
        mean, amplitude = reference[key][:2]
        for value, style in ((mean, "--"), (mean - amplitude, ":"), (mean + amplitude, ":")):
            ax.axhline(scale * value, color="k", linestyle=style, linewidth=0.8)
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    axes[0].set_title("Turek-Hron %s (dashed: published mean, dotted: mean +- amplitude)" % name,
                      fontsize=9)
    axes[1].set_xlabel("t [s]")
    fig.tight_layout()
    fig.savefig(args.png, dpi=120)
    print("wrote", args.png)


if __name__ == "__main__":
    main()
