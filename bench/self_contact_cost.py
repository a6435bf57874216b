#!/usr/bin/env python3
"""Cost of the self and multi-body contact search and mortar evaluation against the number of
facets (issue 13): the rings of examples/rings packed closely (the gap s of rings.geo set
to 0.01 of the radius), N = 10, 50, 200 rings in rows of k = 4, 7, 10, 40 implicit dynamic
steps each (0.1 s: the pile lands and every ring comes into contact with its neighbours).

Printed per N, from summary.json (timings are cumulative seconds, maxima over ranks) and
steps.csv: the facets of the `surface:` interface, its candidate pairs of the last search,
the pairs integrated in the last evaluation (all interfaces, floor and walls included), the
Newton iterations, and per iteration the search seconds (refit and query of the tree over
the whole surface, role assignment) and the mortar seconds (evaluation and linearization
of all interfaces). Then the exponents b of t = a N^b fitted by least
squares in log-log over the runs. A search that grows like N log N has b a little above
1 (1 + 1 / ln N, about 1.1 here); all-pairs work would give b = 2. The run fails (exit 1)
when b > 1.5 for the search or the mortar time or when the candidate pairs per facet grow
by more than a factor of 2 from the smallest to the largest N.

Usage: /usr/bin/python3 bench/self_contact_cost.py [--seam build/bin/seam] [--steps 4]
       [--rings 10,50,200]
"""
import argparse
import csv
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLE = os.path.join(HERE, "..", "examples", "rings")
ROW = {10: 4, 50: 7, 200: 10}  # rings per row (k)


def replace(path, pairs):
    with open(path) as f:
        text = f.read()
    for a, b in pairs:
        if a not in text:
            raise SystemExit("%s: '%s' not found" % (path, a))
        text = text.replace(a, b)
    with open(path, "w") as f:
        f.write(text)


def run(seam, rings, steps):
    folder = tempfile.mkdtemp(prefix="seam_bench_rings_")
    for f in ("rings.yaml", "rings.geo"):
        shutil.copy(os.path.join(EXAMPLE, f), folder)
    k = ROW.get(rings, max(2, int(round(math.sqrt(rings / 2.0)))))
    replace(os.path.join(folder, "rings.geo"),
            [("N = 200; k = 10;", "N = %d; k = %d;" % (rings, k)),
             ("s = 0.1;", "s = 0.01;")])
    replace(os.path.join(folder, "rings.yaml"),
            [("point: [22.2, 0]", "point: [%r, 0]" % (2.0 * k * 1.01 + 0.02)),
             ("end: 1.5, dt: 0.0025", "end: %r, dt: 0.0025" % (0.0025 * steps)),
             ("every: 20", "every: 100000")])
    out = os.path.join(folder, "out")
    subprocess.run([seam, "run", os.path.join(folder, "rings.yaml"), "-o", out, "--quiet"],
                   check=True)
    with open(os.path.join(out, "summary.json")) as f:
        summary = json.load(f)
    with open(os.path.join(out, "steps.csv")) as f:
        iterations = sum(int(r["newton_iterations"]) for r in csv.DictReader(f))
    itf = next(i for i in summary["interfaces"] if i["name"] == "rings")
    shutil.rmtree(folder, ignore_errors=True)
    return dict(rings=rings, facets=itf["slave_elements"], candidates=itf["candidate_pairs"],
                integrated=sum(r["pairs"] for r in summary["ranks_detail"]), iterations=iterations,
                search=summary["timings"]["search"] / iterations,
                mortar=summary["timings"]["mortar"] / iterations,
                wall=summary["wall_seconds"])


def exponent(x, y):
    lx, ly = [math.log(v) for v in x], [math.log(v) for v in y]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    return sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sum((a - mx) ** 2 for a in lx)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--seam", default=os.path.join(HERE, "..", "build", "bin", "seam"))
    p.add_argument("--steps", type=int, default=40)
    p.add_argument("--rings", default="10,50,200")
    args = p.parse_args()
    rows = [run(args.seam, int(n), args.steps) for n in args.rings.split(",")]
    print("%6s %7s %10s %10s %6s %12s %12s %8s" % ("rings", "facets", "candidates",
                                                 "integrated", "iters", "search/it s",
                                                 "mortar/it s", "wall s"))
    for r in rows:
        print("%6d %7d %10d %10d %6d %12.3e %12.3e %8.1f" % (
            r["rings"], r["facets"], r["candidates"], r["integrated"], r["iterations"],
            r["search"], r["mortar"], r["wall"]))
    facets = [r["facets"] for r in rows]
    b_search = exponent(facets, [r["search"] for r in rows])
    b_mortar = exponent(facets, [r["mortar"] for r in rows])
    b_pairs = exponent(facets, [r["candidates"] for r in rows])
    n_log_n = 1.0 + 1.0 / math.log(math.sqrt(facets[0] * facets[-1]))
    print("fitted exponents t ~ N^b: search %.2f, mortar %.2f, candidate pairs %.2f "
          "(N log N: about %.2f; N^2: 2)" % (b_search, b_mortar, b_pairs, n_log_n))
    per_facet = [r["candidates"] / r["facets"] for r in rows]
    ok = b_search <= 1.5 and b_mortar <= 1.5 and per_facet[-1] <= 2.0 * per_facet[0]
    print("candidate pairs per facet %s: %s" % (", ".join("%.2f" % v for v in per_facet),
                                                "PASS" if ok else "FAIL"))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
