#!/usr/bin/env python3
"""Energy and momentum histories of a rings run (README.md figures):

    /usr/bin/python3 examples/rings/plot_rings.py OUTPUT_DIR [-o rings_history.png] [--g 10]

Top: kinetic and strain energy, the work of gravity W_g (midpoint rule,
W += -g dt (p_y,n + p_y,n+1) / 2) and E_kin + E_int - W_g, which contact may only lower.
Bottom: the vertical momentum p_y against the impulse of gravity and of the floor,
-m g t + sum dt N_floor (m from the first step, in free fall p_y = -m g t), and the
horizontal momentum against the impulse of the walls."""
import argparse
import csv
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path) as f:
        return [{k: (float(v) if k != "interface" else v) for k, v in r.items()}
                for r in csv.DictReader(f)]


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("out")
    p.add_argument("-o", "--output", default="rings_history.png")
    p.add_argument("--g", type=float, default=10.0)
    a = p.parse_args()
    steps = read(os.path.join(a.out, "steps.csv"))
    forces = {}
    for r in read(os.path.join(a.out, "interfaces.csv")):
        forces.setdefault(r["step"], {})[r["interface"]] = r["normal_force"]
    mass = -steps[0]["momentum_y"] / (a.g * steps[0]["time"])
    t, ek, ei, wg, bal, py, iy, px, ix = ([0.0] for _ in range(9))
    for r in steps:
        dt = r["time"] - t[-1]
        f = forces.get(r["step"], {})
        wg.append(wg[-1] - a.g * dt * (r["momentum_y"] + py[-1]) / 2)
        iy.append(iy[-1] + dt * (-mass * a.g + f.get("floor", 0.0)))
        ix.append(ix[-1] + dt * (f.get("left", 0.0) - f.get("right", 0.0)))
        t.append(r["time"])
        ek.append(r["kinetic_energy"])
        ei.append(r["internal_energy"])
        bal.append(r["kinetic_energy"] + r["internal_energy"] - wg[-1])
        py.append(r["momentum_y"])
        px.append(r["momentum_x"])
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 7), sharex=True)
    top.plot(t, ek, label="kinetic")
    top.plot(t, ei, label="strain")
    top.plot(t, wg, "k--", label="work of gravity $W_g$")
    top.plot(t, bal, "r", label="$E_{kin} + E_{int} - W_g$")
    top.set_ylabel("energy")
    top.legend()
    top.grid(alpha=0.3)
    bottom.plot(t, py, label="$p_y$")
    bottom.plot(t, iy, "k:", lw=2, label="impulse of gravity and floor")
    bottom.plot(t, px, label="$p_x$")
    bottom.plot(t, ix, "k-.", label="impulse of the walls")
    bottom.set_xlabel("t")
    bottom.set_ylabel("momentum")
    bottom.legend()
    bottom.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(a.output, dpi=110)
    print("mass %.6g; %s written" % (mass, a.output))


if __name__ == "__main__":
    main()
