"""Following a run (issue 17): the time left on every step line, steps.csv readable while the
run goes on.

1. Each step line on the terminal ends with `left T`, the estimate from the mean wall time per
   unit of simulated time so far: it reads as a duration, is 0 s at the last step, and equals
   (wall of the step - wall before the first step) / t * (end - t) within the printed
   precision for a run of equal steps; --quiet prints no step lines.
2. steps.csv is written row by row: read while a long run is going (as `tail -f` would), it
   holds complete rows of consecutive steps; after the run is ended by SIGTERM every row it
   wrote is still there and complete.
3. Fluid and fluid-structure runs print the same step lines, with the time left (0 s at the
   last step).
"""
import csv
import os
import re
import signal
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import geometry  # noqa: E402
import harness as H  # noqa: E402

STATIC = """\
dimension: 2
mesh: {geo: body.geo}
materials: {m: {model: neo_hooke, young: 100, poisson: 0.3}}
bodies: [{region: body, material: m}]
boundary_conditions:
  - {region: left, type: dirichlet, value: [0, 0]}
  - {region: right, type: dirichlet, value: ["0.5*t", 0]}
time: {end: 2, steps: %d}
"""

# Free flight of a spinning rectangle: many cheap steps, no end in sight within the test.
FLIGHT = """\
dimension: 2
mesh: {geo: body.geo}
materials: {m: {model: neo_hooke, young: 100, poisson: 0.3, density: 1}}
bodies: [{region: body, material: m}]
initial_conditions:
  - {region: body, velocity: ["-(y-0.5)", "x-1"]}
time: {integrator: energy_momentum, end: 1000, steps: 100000}
output: {every: 100000}
"""

STEP_LINE = re.compile(r"^step +(\d+) +t = (\S+) +newton +\d+ +residual \S+ +wall +(\S+) s +"
                       r"left (\d+ s|\d+ min \d\d s|\d+ h \d\d min|\?)$")


def seconds(text):
    parts = re.findall(r"(\d+) (h|min|s)", text)
    return sum(int(v) * {"h": 3600, "min": 60, "s": 1}[u] for v, u in parts)


def test_time_left_on_every_step_line():
    n = 8
    work = tempfile.mkdtemp(prefix="seam_progress_")
    H.write_case(work, "body.geo", geometry.rectangle("quad", 0.25))
    path = H.write_case(work, "case.yaml", STATIC % n)
    _, out, _ = H.run(["run", path, "-o", os.path.join(work, "out")])
    _, quiet, _ = H.run(["run", path, "-o", os.path.join(work, "quiet"), "--quiet"])
    H.cleanup(work)
    lines = [l for l in out.splitlines() if l.startswith("step ")]
    if len(lines) != n:
        raise AssertionError("expected %d step lines, got:\n%s" % (n, out))
    parsed = []
    for line in lines:
        m = STEP_LINE.match(line)
        if not m:
            raise AssertionError("step line without a readable time left: %r" % line)
        parsed.append((int(m.group(1)), float(m.group(2)), float(m.group(3)), m.group(4)))
    if parsed[-1][3] != "0 s":
        raise AssertionError("the last step leaves %r, expected 0 s" % parsed[-1][3])
    # The estimate at step k is (w_k - w_0) (end - t_k) / t_k, with w_0 the wall clock when the
    # stepping began: after the set-up (0 <= w_0) and before the first step line (w_0 <= w_1).
    # Both bounds, with the rounding to seconds.
    end = 2.0
    w_1 = parsed[0][2]
    for step, t, wall, left in parsed[:-1]:
        high, low = wall * (end - t) / t, (wall - w_1) * (end - t) / t
        if not low - 1.0 <= seconds(left) <= high + 1.0:
            raise AssertionError("step %d at t = %g, wall %.2f s: left %s, expected %.1f to %.1f s"
                                 % (step, t, wall, left, low, high))
    print("   %s\n   ...\n   %s" % (lines[0], lines[-1]))
    if any(l.startswith("step ") for l in quiet.splitlines()):
        raise AssertionError("--quiet printed step lines:\n%s" % quiet)


def complete_rows(path):
    """The rows of steps.csv as read now, each checked to hold every column."""
    with open(path, newline="") as f:
        text = f.read()
    lines = text.split("\n")
    if not lines[0].startswith("step,time,newton_iterations"):
        raise AssertionError("steps.csv header: %r" % lines[0])
    header = lines[0].split(",")
    # A row is written with its newline in one go: the text ends with one, and no line is cut.
    if not text.endswith("\n"):
        raise AssertionError("steps.csv ends in the middle of a row: %r" % text[-200:])
    rows = list(csv.reader(lines[1:-1]))
    for r in rows:
        if len(r) != len(header) or any(v == "" for v in r[:len(header) - 1]):
            raise AssertionError("incomplete row in steps.csv: %r" % r)
    steps = [int(r[0]) for r in rows]
    if steps != list(range(1, len(steps) + 1)):
        raise AssertionError("steps.csv steps are not 1, 2, ...: %s" % steps[:20])
    return rows


def test_steps_csv_while_running():
    work = tempfile.mkdtemp(prefix="seam_follow_")
    H.write_case(work, "body.geo", geometry.rectangle("quad", 0.5))
    path = H.write_case(work, "case.yaml", FLIGHT)
    out = os.path.join(work, "out")
    steps_csv = os.path.join(out, "steps.csv")
    p = subprocess.Popen([H.SEAM, "run", path, "-o", out, "--quiet"], env=H.mpi_env(),
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        seen = []
        deadline = time.time() + 120
        while time.time() < deadline and p.poll() is None:
            if os.path.exists(steps_csv):
                seen = complete_rows(steps_csv)
                if len(seen) >= 5:
                    break
            time.sleep(0.05)
        if p.poll() is not None:
            raise AssertionError("the run ended (exit %s) before steps.csv could be followed:\n%s"
                                 % (p.returncode, p.stderr.read()[-2000:]))
        if len(seen) < 5:
            raise AssertionError("steps.csv had %d rows after 120 s" % len(seen))
        # Rows grow while the run goes on.
        grown = seen
        while len(grown) <= len(seen) + 2 and time.time() < deadline:
            time.sleep(0.05)
            grown = complete_rows(steps_csv)
        p.send_signal(signal.SIGTERM)
        p.communicate(timeout=60)
        after = complete_rows(steps_csv)
        if len(after) < len(grown) or after[:len(grown)] != grown:
            raise AssertionError("steps.csv lost rows after SIGTERM: %d before, %d after"
                                 % (len(grown), len(after)))
        print("   read %d, then %d rows while running; %d rows after SIGTERM (exit %s)"
              % (len(seen), len(grown), len(after), p.returncode))
    finally:
        if p.poll() is None:
            p.kill()
            p.wait()
        H.cleanup(work)


def check_step_lines(stdout, n, what):
    """n step lines, each with a readable time left, the last one 0 s; returns them."""
    lines = [l for l in stdout.splitlines() if l.startswith("step ")]
    if len(lines) != n:
        raise AssertionError("%s: expected %d step lines, got:\n%s" % (what, n, stdout[-3000:]))
    for line in lines:
        if not STEP_LINE.match(line):
            raise AssertionError("%s: step line without a readable time left: %r" % (what, line))
    if not lines[-1].endswith("left 0 s"):
        raise AssertionError("%s: the last step leaves %r, expected 0 s" % (what, lines[-1]))
    print("   %s: %s\n   ...\n   %s" % (what, lines[0], lines[-1]))
    return lines


def test_time_left_fluid_and_fsi():
    """The step lines of a fluid run (pulsating Poiseuille flow, 6 steps with generalized-alpha)
    and of a fluid-structure run (Turek-Hron FSI1, coarse, 2 load steps) have the same form,
    with the time left."""
    import test_fluid as TF
    import test_restart as TR
    work = tempfile.mkdtemp(prefix="seam_progress_")
    try:
        H.write_case(work, "body.geo", geometry.rectangle("quad_structured", 0.25, 2))
        fluid = H.write_case(work, "fluid.yaml", TF.pulsating_yaml(6))
        _, out, _ = H.run(["run", fluid, "-o", os.path.join(work, "fluid_out")])
        check_step_lines(out, 6, "fluid")
        H.write_case(work, "case.geo", TR.fsi_geo(0.5))
        fsi = H.write_case(work, "fsi.yaml", TR.fsi_yaml("fsi1.yaml", 100, ("steps: 2", "steps: 2")))
        _, out, _ = H.run(["run", fsi, "-o", os.path.join(work, "fsi_out")])
        check_step_lines(out, 2, "fluid-structure")
    finally:
        H.cleanup(work)


if __name__ == "__main__":
    H.main([test_time_left_on_every_step_line, test_steps_csv_while_running,
            test_time_left_fluid_and_fsi])
