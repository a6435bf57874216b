"""The direct solver's kept factorization (la::LinearSolver::allow_factor_reuse, docs/performance.md
"Kept factorizations"): while no contact status has changed since the last MUMPS factorization
of a load step, Newton's next tangent is solved by GMRES preconditioned by that factorization,
to Newton's inexact tolerance (at most 1e-13, what the factorization itself reaches), instead of
being factored.

On examples/torus/torus_hex20.yaml with a coarse mesh (768 hex20 cells, 5 of its 25 load steps,
the example's extrapolated start and c_n):
- reuse happens: fewer factorizations than linear solves, and without reuse (`-- -factor_reuse
  false`) one per solve;
- the converged steps are the same: at every step the wall force, the support reaction and the
  probes' displacements equal those of fresh factorizations to 1e-10, the active nodes equal;
- Newton stays quadratic once the active set has settled (observed order on newton.csv);
- 3 ranks (MUMPS in parallel, with reuse) give the 1-rank results to 1e-10.
"""
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import contact_analysis as C  # noqa: E402
import harness as H  # noqa: E402

EXAMPLES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples")
MESH = {"nc": 8, "nt": 1, "na": 12}  # test_contact.py's coarse hex20 torus
STEPS, OF = 5, 25                    # the first 5 steps of a 25-step run
RTOL = 1e-10
_runs = {}
_dirs = []


def torus(np=1, reuse=True):
    key = (np, reuse)
    if key in _runs:
        return _runs[key]
    work = tempfile.mkdtemp(prefix="seam_reuse_")
    _dirs.append(work)
    with open(os.path.join(EXAMPLES, "torus", "torus.geo")) as f:
        H.write_case(work, "torus.geo", f.read())
    H.write_case(work, "mesh.geo", "".join("%s = %d;\n" % kv for kv in sorted(MESH.items()))
                 + 'Include "torus.geo";\n')
    with open(os.path.join(EXAMPLES, "torus", "torus_hex20.yaml")) as f:
        yaml = f.read()
    for old, new in (("end: 1, steps: 50}", "end: %r, steps: %d}" % (STEPS / OF, STEPS)),
                     ("geo: torus_hex20.geo", "geo: mesh.geo")):
        if old not in yaml:
            raise AssertionError("%r not in torus_hex20.yaml" % old)
        yaml = yaml.replace(old, new)
    for needed in ("initial_guess: extrapolated", "c_n: 2.5"):
        if needed not in yaml:
            raise AssertionError("torus_hex20.yaml no longer has %r" % needed)
    path = H.write_case(work, "torus.yaml", yaml)
    out = H.solve(path, np=np, extra=() if reuse else ("--", "-factor_reuse", "false"))
    _dirs.append(out)
    summary = H.read_json(os.path.join(out, "summary.json"))
    print("   np %d, reuse %s: %d linear solves, %d factorizations, %d Krylov iterations, "
          "%.1f s" % (np, reuse, summary["linear_solves"], summary["preconditioner_builds"],
                      summary["linear_iterations"], summary["wall_seconds"]))
    _runs[key] = (out, summary)
    return _runs[key]


def per_step(out):
    """{step: (wall force, support reaction z, active nodes, probe displacements)}."""
    itf = {int(r["step"]): r for r in H.read_csv(os.path.join(out, "interfaces.csv"))}
    support = {}
    for r in H.read_csv(os.path.join(out, "reactions.csv")):
        if r["region"] == "bottom":
            support[int(r["step"])] = r["fz"]
    probes = {}
    for r in H.read_csv(os.path.join(out, "probes.csv")):
        probes.setdefault(int(r["step"]), []).extend([r["ux"], r["uy"], r["uz"]])
    if len(itf) != STEPS:
        raise AssertionError("%d steps instead of %d" % (len(itf), STEPS))
    return {s: (itf[s]["normal_force"], support[s], int(itf[s]["active_nodes"]), probes[s])
            for s in itf}


def compare(a, b, what):
    pa, pb = per_step(a), per_step(b)
    worst = 0.0
    for s in sorted(pa):
        fa, ra, na, ua = pa[s]
        fb, rb, nb, ub = pb[s]
        if na != nb:
            raise AssertionError("%s, step %d: %d active nodes against %d" % (what, s, nb, na))
        H.assert_close(fb, fa, rtol=RTOL, what="%s, step %d: wall force" % (what, s))
        H.assert_close(rb, ra, rtol=RTOL, what="%s, step %d: support reaction" % (what, s))
        scale = max(abs(v) for v in ua) or 1.0
        for va, vb in zip(ua, ub):
            H.assert_close(vb, va, atol=RTOL * scale, what="%s, step %d: probe" % (what, s))
        worst = max(worst, abs(fb - fa) / abs(fa), abs(rb - ra) / abs(ra))
    print("   %s: largest relative difference of force and reaction %.1e over %d steps"
          % (what, worst, len(pa)))


def check_quadratic(out, min_order=1.6):
    """As test_contact.py: the observed order of the residuals from the last active-set change
    on, above 1e-11 of the step's largest residual."""
    orders = []
    for step, its in sorted(C.newton_table(out).items()):
        last_change = max([k for k, it in enumerate(its) if it[3] != 0], default=0)
        res = [it[1] for it in its[last_change:]]
        o = C.convergence_orders(res, 1e-11 * max(it[1] for it in its))
        print("   step %d: residuals %s, changes %s, orders %s"
              % (step, " ".join("%.1e" % it[1] for it in its),
                 " ".join(str(it[3]) for it in its), " ".join("%.2f" % v for v in o)))
        orders += o
    if not orders or max(orders) < min_order:
        raise AssertionError("Newton not quadratic: observed orders %s" % orders)


def test_reuse_happens():
    _, with_reuse = torus()
    _, fresh = torus(reuse=False)
    if fresh["preconditioner_builds"] != fresh["linear_solves"]:
        raise AssertionError("-factor_reuse false: %d factorizations for %d solves"
                             % (fresh["preconditioner_builds"], fresh["linear_solves"]))
    if with_reuse["preconditioner_builds"] >= with_reuse["linear_solves"]:
        raise AssertionError("no solve reused a factorization (%d factorizations, %d solves)"
                             % (with_reuse["preconditioner_builds"], with_reuse["linear_solves"]))
    if with_reuse["linear_solves"] != fresh["linear_solves"]:
        raise AssertionError("Newton corrections differ: %d with reuse, %d without"
                             % (with_reuse["linear_solves"], fresh["linear_solves"]))


def test_same_steps_as_fresh_factorizations():
    compare(torus(reuse=False)[0], torus()[0], "reuse vs fresh factorizations")


def test_quadratic():
    check_quadratic(torus()[0])


def test_parallel():
    compare(torus()[0], torus(np=3)[0], "np = 3 vs np = 1")
    if torus(np=3)[1]["preconditioner_builds"] >= torus(np=3)[1]["linear_solves"]:
        raise AssertionError("np = 3: no solve reused a factorization")


if __name__ == "__main__":
    try:
        H.main([test_reuse_happens, test_same_steps_as_fresh_factorizations, test_quadratic,
                test_parallel])
    finally:
        H.cleanup(*_dirs)
