#!/usr/bin/env python3
"""Draws contact results of seam runs.

Hertz (examples/hertz_2d, examples/hertz_3d): the nodal contact pressure of the last step
against the distance from the centre of contact, beside Hertz's p0 sqrt(1 - s^2/b^2) for the
load measured at the loaded region (tests/verification/contact_analysis.py has the formulas).

    /usr/bin/python3 scripts/plot_contact.py hertz hertz_2d_out --symmetry 2 \
        --mesh examples/hertz_2d/cylinder.geo -o hertz_2d.png
    /usr/bin/python3 scripts/plot_contact.py hertz hertz_3d_out --symmetry 4 \
        --mesh examples/hertz_3d/sphere.geo -o hertz_3d.png

Cattaneo-Mindlin (examples/cattaneo_mindlin): normal and tangential tractions of the last step
along the contact, the stick and slip nodes, beside Hertz's pressure and Cattaneo's
tangential traction for the measured P and Q (equal elastic bodies, plane strain).

    /usr/bin/python3 scripts/plot_contact.py cattaneo cattaneo_out --mu 0.3 -o cattaneo.png

Forces (examples/ironing): the reaction of a region (--reaction) against t, of one run or of
several side by side.

    /usr/bin/python3 scripts/plot_contact.py forces ironing_2d_out ironing_2d_mu0_out \
        --label "mu = 0.3" --label "mu = 0" --reaction die_ends -o ironing_2d.png

History (examples/torus): contact force, active nodes and Newton iterations per step, of one
run or of several side by side (labels from --label, in order).

    /usr/bin/python3 scripts/plot_contact.py history torus_out -o torus.png
    /usr/bin/python3 scripts/plot_contact.py history torus_out torus_hex20_out \
        --label hex8 --label hex20 -o torus.png
"""
import argparse
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests",
                                "verification"))
import contact_analysis as C  # noqa: E402


def hertz(args):
    args.out = args.out[0]
    name = [f for f in os.listdir(args.out) if f.startswith("interface_")][0]
    rows = C.read_csv(os.path.join(args.out, name))
    dim = 3 if any(abs(r["z"]) > 0 for r in rows) else 2
    estar = args.young / (1 - args.poisson ** 2)
    force = abs(C.reaction(args.out, args.reaction, dim - 1)) * args.symmetry
    b_ref, p_ref = (C.hertz_2d if dim == 2 else C.hertz_3d)(force, args.radius, estar)

    def distance(r, current):
        x = r["x"] + (r["ux"] if current else 0.0)
        y = r["y"] + (r["uy"] if current else 0.0)
        return abs(x) if dim == 2 else math.hypot(x, y)

    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    ss = [1.6 * b_ref * k / 400 for k in range(401)]
    ax.plot([s / b_ref for s in ss], [math.sqrt(max(0.0, 1 - (s / b_ref) ** 2)) for s in ss],
            "k-", label="Hertz, F = %.4g" % force)
    near = [r for r in rows if distance(r, False) < 1.6 * b_ref]
    ax.plot([distance(r, True) / b_ref for r in near], [r["normal_traction"] / p_ref for r in near],
            "x", ms=4, color="0.6", label="seam, per current area at current positions")
    if args.mesh:
        mesh = args.mesh
        if mesh.endswith(".geo"):
            import tempfile
            mesh = C.mesh_geo(mesh, dim, os.path.join(tempfile.mkdtemp(), "mesh.msh"))
        facets, _ = C.slave_facets(C.read_msh(mesh), args.slave)
        tractions, _ = C.reference_tractions(rows, facets)
        p0, b = C.fitted_hertz(rows, dim, current=False, tractions=tractions)
        ax.plot([distance(r, False) / b_ref for r in near],
                [tractions[int(r["node"])] / p_ref for r in near], "o", ms=3,
                label="seam, per reference area at reference positions")
        ax.plot([s / b_ref for s in ss],
                [p0 * math.sqrt(max(0.0, 1 - (s / b) ** 2)) / p_ref for s in ss], "C1--",
                label="fit: b %+.2f %%, p0 %+.2f %%" % (100 * (b / b_ref - 1),
                                                        100 * (p0 / p_ref - 1)))
    ax.set_xlabel("distance from the centre / Hertz " +
                  ("half-width" if dim == 2 else "contact radius"))
    ax.set_ylabel("contact pressure / Hertz peak pressure")
    ax.set_title("%dD Hertz contact, %d active nodes"
                 % (dim, sum(1 for r in rows if C.is_active(r))))
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.output, dpi=130)


def cattaneo(args):
    out = args.out[0]
    rows = C.read_csv(os.path.join(out, "interface_contact.csv"))
    fx, fy = C.reaction(out, args.reaction, 0), C.reaction(out, args.reaction, 1)
    P, Q, mu = abs(fy), abs(fx), args.mu
    estar = args.young / (2.0 * (1.0 - args.poisson ** 2))  # two equal bodies
    a = math.sqrt(4.0 * P * args.radius / (math.pi * estar))
    c = a * math.sqrt(1.0 - Q / (mu * P))
    p0 = 2.0 * P / (math.pi * a)
    active = [r for r in rows if r["status"] != "inactive"]
    xs = [r["x"] + r["ux"] for r in active]
    centre = 0.5 * (min(xs) + max(xs))
    stick = [r["x"] + r["ux"] - centre for r in active if r["status"] == "stick"]
    half = 0.5 * (max(xs) - min(xs))
    peak = max(r["normal_traction"] for r in active)
    print("Cattaneo-Mindlin, two equal elastic bodies in plane strain, mu = %g:" % mu)
    print("  normal load P = %.6g, tangential load Q = %.6g, Q / (mu P) = %.3f" % (P, Q, Q / (mu * P)))
    print("  %-34s %10s %10s %8s" % ("", "theory", "seam", "error"))
    for what, ref, val in (("contact half-width a (Hertz)", a, half),
                           ("peak pressure p0 (Hertz)", p0, peak),
                           ("stick half-width c (Cattaneo)", c,
                            0.5 * (max(stick) - min(stick)) if stick else 0.0)):
        print("  %-34s %10.5f %10.5f %+7.2f %%" % (what, ref, val, 100.0 * (val - ref) / ref))
    print("  %d nodes in contact: %d stick, %d slip" % (len(active), len(stick),
                                                       len(active) - len(stick)))
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    grid = [-1.2 * a + 2.4 * a * k / 600 for k in range(601)]
    ax.plot([x / a for x in grid], [math.sqrt(max(0.0, 1 - (x / a) ** 2)) for x in grid], "k-",
            label="Hertz pressure p / p0")
    q = [mu * (math.sqrt(max(0.0, 1 - (x / a) ** 2)) -
               (c / a) * math.sqrt(max(0.0, 1 - (x / c) ** 2))) for x in grid]
    ax.plot([x / a for x in grid], q, "C0-",
            label="Cattaneo traction q / p0, c/a = %.3f" % (c / a))
    for status, marker, color in (("stick", "o", "C2"), ("slip", "s", "C3")):
        sel = [r for r in active if r["status"] == status]
        ax.plot([(r["x"] + r["ux"] - centre) / a for r in sel],
                [r["tangential_traction"] / p0 for r in sel], marker, ms=4, color=color,
                mfc="none", label="seam q / p0, %s (%d nodes)" % (status, len(sel)))
    ax.plot([(r["x"] + r["ux"] - centre) / a for r in active],
            [r["normal_traction"] / p0 for r in active], "x", ms=3, color="0.5",
            label="seam p / p0")
    ax.axvspan(-c / a, c / a, color="C2", alpha=0.08)
    ax.set_xlabel("x / a (current configuration, from the centre of contact)")
    ax.set_ylabel("traction / p0")
    ax.set_title("Cattaneo-Mindlin, Q / (mu P) = %.3f" % (Q / (mu * P)))
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(args.output, dpi=130)


def labelled_runs(args):
    """(output directory, label) of every run given, labels from --label in order."""
    labels = args.label or [os.path.basename(os.path.normpath(o)) for o in args.out]
    return list(zip(args.out, labels))


def forces(args):
    n = "f" + args.normal  # the pressing direction: y in 2D, z in 3D
    fig, ax = plt.subplots(2, 1, figsize=(6, 6), sharex=True)
    for k, (out, label) in enumerate(labelled_runs(args)):
        rows = [r for r in C.read_csv(os.path.join(out, "reactions.csv"))
                if r["region"] == args.reaction]
        t = [r["time"] for r in rows]
        ax[0].plot(t, [r["fx"] for r in rows], "-", color="C%d" % k, label=label + ": F_x")
        ax[0].plot(t, [-r[n] for r in rows], "--", color="C%d" % k,
                   label=label + ": -F_" + args.normal)
        ax[1].plot(t, [abs(r["fx"] / r[n]) if r[n] else 0.0 for r in rows], "-",
                   color="C%d" % k, label=label)
    ax[0].set_ylabel("reaction at %s" % args.reaction)
    ax[1].set_ylabel("|F_x| / |F_%s|" % args.normal)
    ax[1].set_xlabel("t (press for t <= 1, then slide)")
    ax[0].legend(fontsize=8)
    ax[1].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.output, dpi=130)


def history(args):
    fig, ax = plt.subplots(3, 1, figsize=(6, 7), sharex=True)
    for k, (out, label) in enumerate(labelled_runs(args)):
        itf = C.read_csv(os.path.join(out, "interfaces.csv"))
        steps = C.read_csv(os.path.join(out, "steps.csv"))
        color = "C%d" % k
        ax[0].plot([r["time"] for r in itf], [r["normal_force"] for r in itf], "-", color=color,
                   label=label)
        ax[1].plot([r["time"] for r in itf], [r["active_nodes"] for r in itf], "-", color=color)
        ax[2].step([r["time"] for r in steps], [r["newton_iterations"] for r in steps], "-",
                   color=color, where="post")
    ax[0].set_ylabel("contact force")
    ax[1].set_ylabel("active nodes")
    ax[2].set_ylabel("Newton iterations")
    ax[2].set_xlabel("t")
    if len(args.out) > 1:
        ax[0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.output, dpi=130)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("kind", choices=["hertz", "cattaneo", "forces", "history"])
    p.add_argument("out", nargs="+", help="seam output directory (history: one or more)")
    p.add_argument("--label", action="append", help="history: a label per output directory")
    p.add_argument("-o", "--output", default="contact.png")
    p.add_argument("--radius", type=float, default=1.0)
    p.add_argument("--young", type=float, default=1.0)
    p.add_argument("--poisson", type=float, default=0.3)
    p.add_argument("--symmetry", type=float, default=1.0)
    p.add_argument("--mu", type=float, default=0.3, help="cattaneo: friction coefficient")
    p.add_argument("--reaction", default="top")
    p.add_argument("--normal", default="y", choices=["y", "z"],
                   help="forces: the pressing direction (y in 2D, z in 3D)")
    p.add_argument("--mesh", help="the run's .msh or .geo: adds the traction per reference area")
    p.add_argument("--slave", default="surface", help="slave region (with --mesh)")
    args = p.parse_args()
    {"hertz": hertz, "cattaneo": cattaneo, "forces": forces, "history": history}[args.kind](args)


if __name__ == "__main__":
    main()
