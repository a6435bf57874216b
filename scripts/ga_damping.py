#!/usr/bin/env python3
"""The amplitude and phase of one step of generalized-alpha for first-order systems (Jansen,
Whiting & Hulbert 2000, as seam's fluids use it) on y' = i omega y: how much the integrator
damps an oscillation of the flow, e.g. the vortex shedding of DFG 2D-3 (period about 0.4, so
omega dt = 0.16 at dt = 0.01).

    /usr/bin/python3 scripts/ga_damping.py [--omega-dt 0.157 0.0785]

Printed per rho_inf and omega dt: the amplitude factor of the principal root per step, its
damping over 170 steps (the growth of the 2D-3 shedding) and the ratio of its phase speed to
the exact one.
"""
import argparse
import cmath

import numpy as np


def principal_root(rho_inf, wdt):
    am = (3 - rho_inf) / (2 * (1 + rho_inf))
    af = 1 / (1 + rho_inf)
    g = 0.5 + am - af
    lam = 1j * wdt
    # am yd1 + (1 - am) yd0 = lam ((1 - af) y0 + af y1);  y1 = y0 + (1 - g) yd0 + g yd1 (dt = 1)
    A = np.array([[-lam * af, am], [1, -g]], dtype=complex)
    B = np.array([[lam * (1 - af), -(1 - am)], [1, 1 - g]], dtype=complex)
    roots = np.linalg.eigvals(np.linalg.solve(A, B))
    return min(roots, key=lambda z: abs(z - cmath.exp(lam)))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--omega-dt", type=float, nargs="+", default=[0.157, 0.0785])
    a = ap.parse_args()
    print("%8s %9s %14s %18s %12s" % ("rho_inf", "omega dt", "1 - |root|", "loss in 170 steps",
                                      "phase ratio"))
    for rho in (0.0, 0.5, 0.8, 1.0):
        for wdt in a.omega_dt:
            z = principal_root(rho, wdt)
            print("%8.2f %9.4f %14.3e %17.4f%% %12.6f" % (rho, wdt, 1 - abs(z),
                                                         100 * (1 - abs(z) ** 170),
                                                         cmath.phase(z) / wdt))


if __name__ == "__main__":
    main()
