"""The seed's L-shaped block in CI: a short run (t <= 0.8, the pulse ends at 0.5) of
examples/l_block on its coarse mesh. Once the load is off, with the energy-momentum method the
total energy and the linear and angular momentum are constant to 1e-10 (relative); with
generalized-alpha the energy does not grow.
"""
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness as H  # noqa: E402

EXAMPLE = os.path.join(H.HERE, "..", "..", "examples", "l_block")


def run(integrator, np=1):
    work = tempfile.mkdtemp(prefix="seam_lblock_")
    with open(os.path.join(EXAMPLE, "l_block.yaml")) as f:
        text = f.read()
    text = text.replace("end: 5.0", "end: 0.8").replace("steps: 500", "steps: 40")
    text = text.replace("integrator: energy_momentum", "integrator: %s" % integrator)
    with open(os.path.join(EXAMPLE, "l_block.geo")) as f:
        H.write_case(work, "l_block.geo", f.read())
    path = H.write_case(work, "l_block.yaml", text)
    out = H.solve(path, np=np)
    rows = H.read_csv(os.path.join(out, "steps.csv"))
    H.cleanup(work, out)
    return [r for r in rows if r["time"] > 0.5 + 1e-9], rows


def test_energy_momentum_conserves_after_the_pulse():
    free, rows = run("energy_momentum")
    if max(r["internal_energy"] for r in free) <= 0 or len(free) < 10:
        raise AssertionError("no free flight to check")
    for key in ("total_energy", "momentum_x", "momentum_y", "momentum_z", "angular_momentum_x",
                "angular_momentum_y", "angular_momentum_z"):
        values = [r[key] for r in free]
        scale = max(abs(v) for v in values)
        if scale == 0:
            continue
        d = (max(values) - min(values)) / scale
        print("   %s: %.10g, relative drift %.2e" % (key, values[-1], d))
        if d > 1e-10:
            raise AssertionError("%s drifts by %.3e after the load is off" % (key, d))


def test_generalized_alpha_energy_does_not_grow():
    free, rows = run("generalized_alpha")
    energy = [r["total_energy"] for r in free]
    print("   generalized-alpha after the pulse: energy %.10g -> %.10g" % (energy[0], energy[-1]))
    if max(energy) > energy[0] * (1 + 1e-3) or energy[-1] > energy[0]:
        raise AssertionError("energy grows: %s" % energy)


if __name__ == "__main__":
    H.main([test_energy_momentum_conserves_after_the_pulse,
            test_generalized_alpha_energy_does_not_grow])
