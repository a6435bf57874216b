#!/usr/bin/env python3
"""Histories of a tori_impact run (README.md figure):

    /usr/bin/python3 examples/tori_impact/plot_tori.py OUTPUT_DIR [-o tori_history.png]
    /usr/bin/python3 examples/tori_impact/plot_tori.py --energy DIR:LABEL ... [-o energy.png]

Top: kinetic, strain and total energy, relative to the energy at the start (no loads and no
supports: the total may only fall). Middle: the contact force and the number of active
nodes. Bottom: the displacement along x of A's facing equator (probe 0) and of B's facing
rim (probe 3), and B's free flight -v t for comparison. With --energy: the total energy of
several runs (output directory and label), relative to its start."""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tests",
                                "verification"))
from contact_analysis import read_csv as read  # noqa: E402


def plot_energies(runs, output):
    fig, ax = plt.subplots(figsize=(8, 4))
    for run in runs:
        out, _, label = run.partition(":")
        steps = read(os.path.join(out, "steps.csv"))
        e0 = steps[0]["total_energy"]
        ax.plot([r["time"] for r in steps], [r["total_energy"] / e0 for r in steps],
                label=label or out)
    ax.set_xlabel("t")
    ax.set_ylabel("total energy / initial energy")
    ax.legend()
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(output, dpi=110)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("out", nargs="+")
    p.add_argument("-o", "--output", default="tori_history.png")
    p.add_argument("--energy", action="store_true",
                   help="total energy of each run OUT:LABEL on one plot")
    a = p.parse_args()
    if a.energy:
        plot_energies(a.out, a.output)
        return
    a.out = a.out[0]
    steps = read(os.path.join(a.out, "steps.csv"))
    force = {r["step"]: r["normal_force"] for r in read(os.path.join(a.out, "interfaces.csv"))}
    probes = {}
    for r in read(os.path.join(a.out, "probes.csv")):
        probes.setdefault(r["step"], {})[int(r["probe"])] = r["ux"]
    e0 = steps[0]["total_energy"]
    t = [r["time"] for r in steps]
    fig, (top, mid, bottom) = plt.subplots(3, 1, figsize=(8, 9), sharex=True)
    top.plot(t, [r["kinetic_energy"] / e0 for r in steps], label="kinetic")
    top.plot(t, [r["internal_energy"] / e0 for r in steps], label="strain")
    top.plot(t, [r["total_energy"] / e0 for r in steps], "r", label="total")
    top.set_ylabel("energy / initial energy")
    top.legend()
    top.grid(alpha=0.3)
    mid.plot(t, [force.get(r["step"], 0.0) for r in steps], label="contact force")
    mid.set_ylabel("normal force")
    twin = mid.twinx()
    twin.plot(t, [r["active_nodes"] for r in steps], "k:", label="active nodes")
    twin.set_ylabel("active nodes")
    mid.grid(alpha=0.3)
    tp = [r["time"] for r in steps if r["step"] in probes]
    for k, name in ((0, "A's facing equator"), (3, "B's facing rim")):
        bottom.plot(tp, [probes[r["step"]][k] for r in steps if r["step"] in probes], label=name)
    first = min(probes)
    v = -probes[first][3] / next(r["time"] for r in steps if r["step"] == first)
    bottom.plot(t, [-v * x for x in t], "k--", label="free flight of B")
    bottom.set_ylabel("$u_x$")
    bottom.set_xlabel("t")
    bottom.legend()
    bottom.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(a.output, dpi=110)
    print("tori history drawn in", a.output)


if __name__ == "__main__":
    main()
