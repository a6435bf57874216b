"""The extrapolated start of static load steps (`solver.newton.initial_guess`, docs/input.md
§6.2): Newton starts step n+1 at u_n + (t_{n+1} - t_n)/(t_n - t_{n-1}) (u_n - u_{n-1}) instead
of u_n, so a growing contact zone is found at the first evaluation.

- Hertz sphere on a rigid plane (examples/hertz_3d: tet4, 3240 dofs, 5 load steps, the contact
  zone grows from 11 to 47 nodes): from the last converged state (`previous`) the steps take
  5 4 4 4 4 Newton iterations; extrapolated (quadratic from the third step on, linear in the
  second) 5 4 3 3 3. The test asks step 1 to be unchanged (nothing to extrapolate from), the
  quadratically extrapolated steps to take at most MAX_ITERATIONS, none more than with
  `previous`, and fewer in all. The converged steps are the same
  equilibria: active sets equal, every slave node's displacement and nodal pressure and the
  reaction of the cut equal to 1e-8 of their largest values (the Newton tolerance is 1e-10).
- The same extrapolated run on 3 ranks equals the one on 1 rank to 1e-8.
- Bad input: an unknown `initial_guess` exits 1 with a message at its line.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness as H  # noqa: E402

# Steps 3..5 of the Hertz example. Measured: `previous` 4 4 4, extrapolated 3 3 3.
MAX_ITERATIONS = 3
_dirs = []


def hertz(guess, np=1):
    work, yaml = H.copy_example("hertz_3d", "hertz_3d.yaml", replace=[(
        "initial_guess: extrapolated}", "initial_guess: %s}" % guess)])
    out = H.solve(yaml, np=np)
    _dirs.extend([work, out])
    return out


def rows(out, name):
    return H.read_csv(os.path.join(out, name))


def iterations(out):
    return [int(r["newton_iterations"]) for r in rows(out, "steps.csv")]


def assert_same_state(a, b, what):
    """Active sets, slave displacements and pressures, the cut's reaction: equal to 1e-8."""
    sa = [r["active_nodes"] for r in rows(a, "steps.csv")]
    sb = [r["active_nodes"] for r in rows(b, "steps.csv")]
    if sa != sb:
        raise AssertionError("%s: active nodes per step %s vs %s" % (what, sa, sb))
    ca = {int(r["node"]): r for r in rows(a, "interface_contact.csv")}
    cb = {int(r["node"]): r for r in rows(b, "interface_contact.csv")}
    if ca.keys() != cb.keys():
        raise AssertionError("%s: different slave nodes" % what)
    worst = {}
    for keys in (("ux", "uy", "uz"), ("normal_traction",)):
        scale = max(abs(r[k]) for r in ca.values() for k in keys)
        err = max(abs(ca[n][k] - cb[n][k]) for n in ca for k in keys) / scale
        worst[keys[0]] = err
        if err > 1e-8:
            raise AssertionError("%s: %s differ by %.2e of their largest value" % (what, keys, err))
    for ra, rb in zip(rows(a, "reactions.csv"), rows(b, "reactions.csv")):
        if ra["region"] == "top":
            H.assert_close(rb["fz"], ra["fz"], rtol=1e-8, what="%s: top reaction, step %d"
                           % (what, ra["step"]))
    print("   %s: equal active sets; displacement %.1e, pressure %.1e of the largest"
          % (what, worst["ux"], worst["normal_traction"]))


def test_hertz_fewer_iterations_same_solution():
    previous, extrapolated = hertz("previous"), hertz("extrapolated")
    ip, ie = iterations(previous), iterations(extrapolated)
    print("   Newton iterations per step: previous %s, extrapolated %s" % (ip, ie))
    if ie[0] != ip[0]:
        raise AssertionError("step 1 has nothing to extrapolate from: %d vs %d" % (ie[0], ip[0]))
    if max(ie[2:]) > MAX_ITERATIONS:
        raise AssertionError("extrapolated: steps 3.. need %s > %d iterations"
                             % (ie[2:], MAX_ITERATIONS))
    if any(e > p for e, p in zip(ie, ip)):
        raise AssertionError("extrapolated needs more iterations than previous in a step")
    if sum(ie) >= sum(ip):
        raise AssertionError("extrapolated: %d iterations in all, previous %d" % (sum(ie), sum(ip)))
    assert_same_state(previous, extrapolated, "extrapolated vs previous")


def test_hertz_np3():
    a, b = hertz("extrapolated"), hertz("extrapolated", np=3)
    if iterations(a) != iterations(b):
        raise AssertionError("iterations np = 1 %s, np = 3 %s" % (iterations(a), iterations(b)))
    assert_same_state(a, b, "np = 3 vs np = 1")


def test_bad_value():
    work, yaml = H.copy_example("hertz_3d", "hertz_3d.yaml", replace=[(
        "initial_guess: extrapolated}", "initial_guess: linear}")])
    _dirs.append(work)
    code, out, err = H.run(["run", yaml, "-o", os.path.join(work, "out")], check=False)
    text = out + err
    if code != 1 or "initial_guess" not in text or "extrapolated" not in text:
        raise AssertionError("exit %d, message:\n%s" % (code, text[-1500:]))
    print("   " + [l for l in text.splitlines() if "initial_guess" in l][0].strip())


if __name__ == "__main__":
    try:
        H.main([test_hertz_fewer_iterations_same_solution, test_hertz_np3, test_bad_value])
    finally:
        H.cleanup(*_dirs)
