#!/usr/bin/env python3
"""Mean, amplitude and frequency of a periodic history, as the Turek-Hron benchmarks define
them (Turek & Hron 2006, sec. 3: over the last period, mean = (max + min) / 2, amplitude =
(max - min) / 2, frequency = 1 / period), from seam's probes.csv and forces.csv. The extrema
are those of the parabola through each sampled local extremum and its two neighbours.

    python3 scripts/periodic_state.py OUT             # probe 0 (point A) and force group 0
    python3 scripts/periodic_state.py OUT --fsi3      # also against the FSI3 reference values
    python3 scripts/periodic_state.py OUT --fsi2      # also against the FSI2 reference values
    python3 scripts/periodic_state.py OUT --cfd3      # drag and lift against CFD3's

Plain Python (no numpy): tests/verification imports it (test_turek_hron.py, test_fsi.py).
"""
import argparse
import csv
import os
import sys

# Turek & Hron 2006, Table 12 (FSI3, finest mesh and step): mean, amplitude, frequency.
FSI3 = {"ux": (-2.69e-3, 2.53e-3, 10.9), "uy": (1.48e-3, 34.38e-3, 5.3),
        "drag": (457.3, 22.66, 10.9), "lift": (2.22, 149.78, 5.3)}
# The tolerances of issue 15 on the FSI3 figures (relative): (what, key, part, tolerance).
FSI3_CHECKS = [("u_y(A) amplitude", "uy", "amplitude", 0.05),
               ("u_y(A) frequency", "uy", "frequency", 0.03),
               ("mean drag", "drag", "mean", 0.02),
               ("lift amplitude", "lift", "amplitude", 0.15)]
# Turek & Hron 2006, Table 11 (FSI2, finest mesh and step), and issue 15's tolerances on the
# amplitude of u_y(A) (5 %) and its frequency (FSI3's 3 %, the issue names no other).
FSI2 = {"ux": (-14.58e-3, 12.44e-3, 3.8), "uy": (1.23e-3, 80.6e-3, 2.0),
        "drag": (208.83, 73.75, 3.8), "lift": (0.88, 234.2, 2.0)}
FSI2_CHECKS = [("u_y(A) amplitude", "uy", "amplitude", 0.05),
               ("u_y(A) frequency", "uy", "frequency", 0.03)]
# Turek & Hron 2006 (CFD3, rigid cylinder and flag, finest mesh and step): drag and
# lift over cylinder + flag, mean, amplitude, frequency (4.3956 Hz for both: the drag's
# secondary maximum in each period of the lift is the lower one and is merged, see periods()).
CFD3 = {"drag": (439.45, 5.6183, 4.3956), "lift": (-11.893, 437.81, 4.3956)}
# The tolerances of issue 14 on the CFD3 figures (relative).
CFD3_CHECKS = [("mean drag", "drag", "mean", 0.01),
               ("lift frequency", "lift", "frequency", 0.01)]


def extremum(t, u, i):
    """Time and value of the parabola through the samples i-1, i, i+1."""
    a = (u[i + 1] - 2 * u[i] + u[i - 1]) / 2
    b = (u[i + 1] - u[i - 1]) / 2
    if a == 0:
        return t[i], u[i]
    s = -b / (2 * a)
    return t[i] + s * (t[i + 1] - t[i]), u[i] - b * b / (4 * a)


def extrema(t, u):
    """The interpolated local maxima and minima of a sampled history: two lists of (t, u)."""
    maxima = [extremum(t, u, i) for i in range(1, len(u) - 1)
              if u[i] > u[i - 1] and u[i] >= u[i + 1]]
    minima = [extremum(t, u, i) for i in range(1, len(u) - 1)
              if u[i] < u[i - 1] and u[i] <= u[i + 1]]
    return maxima, minima


def periods(t, u):
    """Per period, from the last backwards: (t_end, mean, amplitude, frequency), each period
    from one maximum to the next with the minimum between them. A history with secondary
    extrema (a drag with a small bump per period) keeps, per period, the largest maximum and
    the smallest minimum: only maxima above the middle of the extremes start periods, so a
    secondary maximum below it is merged and one above it is taken for a period (FSI2's lift;
    tests/verification/test_periodic_state.py)."""
    maxima, minima = extrema(t, u)
    if len(maxima) < 2:
        return []
    # The dominant period: the median spacing of the maxima that stand out (above the mean).
    mid = (max(m[1] for m in maxima) + min(m[1] for m in minima)) / 2 if minima else 0
    tops = [m for m in maxima if m[1] > mid]
    if len(tops) < 2:
        return []
    out = []
    for k in range(len(tops) - 1, 0, -1):
        t0, t1 = tops[k - 1][0], tops[k][0]
        lows = [m[1] for m in minima if t0 < m[0] < t1]
        if not lows:
            continue
        hi, lo = tops[k][1], min(lows)
        out.append((t1, (hi + lo) / 2, (hi - lo) / 2, 1 / (t1 - t0)))
    return out


def periodic_state(t, u, last=1):
    """Mean, amplitude and frequency averaged over the last `last` periods; None if the history
    has fewer."""
    p = periods(t, u)[:last]
    if len(p) < last or not p:
        return None
    n = len(p)
    return {"mean": sum(x[1] for x in p) / n, "amplitude": sum(x[2] for x in p) / n,
            "frequency": sum(x[3] for x in p) / n, "periods": len(periods(t, u)),
            "t_end": p[0][0]}


def read(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def histories(out, probe=0, group=None):
    """{'ux', 'uy': (t, values) of the probe; 'drag', 'lift': of the force group} from a run's
    output directory (force group: the first one unless named)."""
    h = {}
    rows = [r for r in read(os.path.join(out, "probes.csv")) if int(r["probe"]) == probe]
    t = [float(r["time"]) for r in rows]
    for key in ("ux", "uy"):
        h[key] = (t, [float(r[key]) for r in rows])
    path = os.path.join(out, "forces.csv")
    if os.path.exists(path):
        rows = read(path)
        if rows:
            name = group or rows[0]["name"]
            rows = [r for r in rows if r["name"] == name]
            t = [float(r["time"]) for r in rows]
            h["drag"] = (t, [float(r["fx"]) for r in rows])
            h["lift"] = (t, [float(r["fy"]) for r in rows])
    return h


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("output", help="a run's output directory")
    parser.add_argument("--last", type=int, default=3, help="periods to average (default 3)")
    parser.add_argument("--fsi3", action="store_true",
                        help="compare with Turek & Hron's FSI3 values and issue 15's tolerances")
    parser.add_argument("--fsi2", action="store_true",
                        help="compare with Turek & Hron's FSI2 values and issue 15's tolerances")
    parser.add_argument("--cfd3", action="store_true",
                        help="compare with Turek & Hron's CFD3 values and issue 14's tolerances")
    parser.add_argument("--group", help="the force group (default: the first in forces.csv)")
    args = parser.parse_args()
    h = histories(args.output, group=args.group)
    reference, checks = ((FSI3, FSI3_CHECKS) if args.fsi3 else (FSI2, FSI2_CHECKS) if args.fsi2
                         else (CFD3, CFD3_CHECKS))
    compare = args.fsi3 or args.fsi2 or args.cfd3
    if args.cfd3:
        h = {key: h[key] for key in ("drag", "lift") if key in h}
    failed = False
    states = {}
    for key, (t, u) in h.items():
        s = periodic_state(t, u, args.last)
        states[key] = s
        if s is None:
            print("%-5s fewer than %d periods in t <= %g" % (key, args.last, t[-1] if t else 0))
            continue
        line = ("%-5s mean %+.5e  amplitude %.5e  frequency %.4f Hz  (last %d of %d periods, "
                "to t = %.3f)" % (key, s["mean"], s["amplitude"], s["frequency"], args.last,
                                   s["periods"], s["t_end"]))
        if compare:
            line += "   reference %+.4e +- %.4e, %.4g Hz" % reference[key]
        print(line)
        # Settled? The amplitude of each of the last periods against their mean.
        p = periods(t, u)[:args.last]
        spread = max(abs(x[2] - s["amplitude"]) for x in p) / s["amplitude"]
        print("      amplitude spread over these periods %.2f %%" % (100 * spread))
    if compare:
        for what, key, part, tol in checks:
            ref = reference[key][("mean", "amplitude", "frequency").index(part)]
            s = states.get(key)
            if s is None:
                print("%-18s not measured" % what)
                failed = True
                continue
            err = s[part] / ref - 1
            ok = abs(err) <= tol
            failed |= not ok
            print("%-18s %.5g against %.5g: %+.2f %% (tolerance %g %%) %s"
                  % (what, s[part], ref, 100 * err, 100 * tol, "ok" if ok else "OUTSIDE"))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
