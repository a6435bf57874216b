"""Serial against parallel (issue: foundation): the flagship Neo-Hookean block (large
compression, 10 Newton load steps) and the tied hex/tet blocks give the same probes and
reactions at np = 1 and np = 3 (1e-8 relative), and the iterative solver (GMRES + GAMG with the
rigid-body near-null space) at np = 3 agrees with the direct one.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness as H  # noqa: E402


def run_example(name, yaml, np, replace=()):
    work, path = H.copy_example(name, yaml, replace)
    out = H.solve(path, np=np)
    probes = H.read_csv(os.path.join(out, "probes.csv"))
    reactions = H.read_csv(os.path.join(out, "reactions.csv"))
    H.cleanup(work, out)
    return probes, reactions


def compare(a, b, keys, rtol, what):
    scale = max(abs(r[k]) for r in a for k in keys) or 1.0
    if len(a) != len(b):
        raise AssertionError("%s: %d rows against %d" % (what, len(a), len(b)))
    worst = 0.0
    for ra, rb in zip(a, b):
        for k in keys:
            worst = max(worst, abs(ra[k] - rb[k]) / scale)
    print("   %s: largest difference %.2e (relative to %.3g)" % (what, worst, scale))
    if worst > rtol:
        raise AssertionError("%s differ by %.3e" % (what, worst))


def check(name, yaml, rtol=1e-8, replace=(), replace_parallel=()):
    p1, r1 = run_example(name, yaml, 1, replace)
    p3, r3 = run_example(name, yaml, 3, tuple(replace) + tuple(replace_parallel))
    compare(p1, p3, ("ux", "uy", "uz"), rtol, "%s probes" % name)
    compare(r1, r3, ("fx", "fy", "fz"), rtol, "%s reactions" % name)


def test_neo_hooke_block_np3(): check("neo_hooke_block", "block.yaml")
def test_tied_blocks_np3(): check("tied_blocks", "blocks.yaml")
def test_neo_hooke_block_iterative_np3():
    check("neo_hooke_block", "block.yaml", rtol=1e-6,
          replace_parallel=(("linear: direct", "linear: iterative"),))


if __name__ == "__main__":
    H.main([test_neo_hooke_block_np3, test_tied_blocks_np3, test_neo_hooke_block_iterative_np3])
