#!/usr/bin/env python3
"""How much of the contact sides each rank holds against what it reads (docs/parallel.md,
"What is still replicated"): four cases of tests/verification/test_distribution.py at np 3
(the Hertz sphere on a block, six steps with the independent distribution; the 2D ironing
with friction, IRONING_SHORT; the 7-ring pile and the two rings with friction, both
energy-momentum), one markdown row each from summary.json `ranks_detail`: the sides' facets
held per rank (`contact_side_facets_held`), those read at the last evaluation
(`contact_side_facets_read`), the interface nodes gathered (`contact_interface_nodes_gathered`)
and the cells held. The rebalancing measures time by default, so the counts can differ by
a few facets from run to run.

Usage: SEAM=build/bin/seam python3 bench/contact_sides_held.py [--np 3]
"""
import argparse
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "verification"))

import test_distribution as T  # noqa: E402 - the cases as the tests run them


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--np", type=int, default=3)
    args = parser.parse_args()
    np = args.np
    cases = [
        ("Hertz sphere on a block (six steps)", lambda: T.hertz(np, "independent")),
        ("2D ironing with friction",
         lambda: T.run_example("ironing", "ironing_2d.yaml", np, T.IRONING_SHORT)),
        ("7-ring pile (energy-momentum)", lambda: T.pile_case(np)),
        ("2 rings with friction (energy-momentum)", lambda: T.friction_rings_case(np)),
    ]
    print("| case | side facets held per rank | read per rank | interface nodes gathered per "
          "rank | cells per rank |")
    print("|---|---|---|---|---|")
    try:
        for name, run in cases:
            detail = T.ranks_detail(run())
            column = lambda key: " / ".join(str(r.get(key)) for r in detail)  # noqa: E731
            print("| %s | %s | %s | %s | %s |" % (
                name, column("contact_side_facets_held"), column("contact_side_facets_read"),
                column("contact_interface_nodes_gathered"), column("cells")), flush=True)
    finally:
        T.H.cleanup(*T._dirs)


if __name__ == "__main__":
    main()
