"""The contact patches between rings and the sides their slave facets are on, from a run with
SEAM_CONTACT_TRACE=3 (np 1), whose lines name every weighted-gap block (slave facet, master
facet) that appears, disappears or changes at each evaluation.

    /usr/bin/python3 examples/rings/patch_sides.py run.log out/results_00163.vtu
    /usr/bin/python3 examples/rings/patch_sides.py run.log out/results_00163.vtu 164 86,87,96

The .vtu gives the rings (connected groups of cells; any output of the run). Without more
arguments: per step, at the first evaluation of its first attempt, the ring pairs whose
patch has blocks in both directions (slave facets on both rings), split by the smaller
direction's count (1 or 2 blocks: a stray block at the patch's end; 3 or more: a patch split
between the roles). With STEP and RINGS: the blocks among those rings at that evaluation."""
import re
import sys
from collections import Counter

import numpy as np

from inside_other_ring import arrays, rings

PAIR = re.compile(r"  rings pair (new|gone|changed): slave (\d+)-(\d+) master (\d+)-(\d+): "
                  r"(block|pre-check|no overlap)")
FIRST = re.compile(r"  step (\d+)  iteration 0  rings:")


def rings_of(path):
    a = arrays(path)
    return rings(a["connectivity"].reshape(-1, 4), len(a["Points"]))


def first_evaluations(log):
    """(step, block set) at the first evaluation of each step's first attempt."""
    blocks, seen = set(), set()
    for line in open(log):
        m = PAIR.match(line)
        if m:
            kind, status = m.group(1), m.group(6)
            key = tuple(int(v) for v in m.group(2, 3, 4, 5))
            if kind == "gone" or (kind == "changed" and status != "block"):
                blocks.discard(key)
            elif status == "block":
                blocks.add(key)
            continue
        m = FIRST.match(line)
        if m and m.group(1) not in seen:
            seen.add(m.group(1))
            pending = int(m.group(1))
            continue
        # The pair lines of an evaluation follow its summary line; the next summary closes it.
        if line.startswith("  step ") and "floor:" in line and seen and pending is not None:
            yield pending, set(blocks)
            pending = None


if __name__ == "__main__":
    ring = rings_of(sys.argv[2])
    for step, blocks in first_evaluations(sys.argv[1]):
        d = Counter((ring[k[0]], ring[k[2]]) for k in blocks)
        if len(sys.argv) > 4:
            if step != int(sys.argv[3]):
                continue
            chosen = {int(v) for v in sys.argv[4].split(",")}
            print("step %d, blocks (slave ring -> master ring): %s" % (step, {
                "%d->%d" % p: n for p, n in sorted(d.items()) if set(p) <= chosen}))
            for k in sorted(blocks):
                if ring[k[0]] in chosen and ring[k[2]] in chosen:
                    print("  %d->%d slave %d-%d master %d-%d" % (ring[k[0]], ring[k[2]], *k))
            break
        small = [min(d[(a, b)], d[(b, a)]) for (a, b) in d if a < b and (b, a) in d]
        print("step %d: ring pairs in contact %d, with slave facets on both rings %d (smaller "
              "side 1-2 blocks %d, 3 or more %d)" % (step, len({tuple(sorted(p)) for p in d}),
                                                     len(small), sum(v < 3 for v in small),
                                                     sum(v >= 3 for v in small)))
