"""Helpers for seam's verification tests: run the executable (serially or under mpirun),
read the CSV and JSON outputs, and assert with readable messages.

Every case computes its reference values from formulas, never from an earlier seam run.
Environment: SEAM (path of the seam executable), MPIEXEC (path of mpirun).
"""
import csv
import functools
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import time

SEAM = os.environ.get("SEAM", "seam")
FULL = os.environ.get("SEAM_FULL") == "1"
MPIEXEC = os.environ.get("MPIEXEC", "mpirun")
HERE = os.path.dirname(os.path.abspath(__file__))


def mpi_env():
    env = dict(os.environ)
    env.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
    env.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    env.setdefault("OMPI_MCA_rmaps_base_oversubscribe", "1")
    # Ranks waiting in a collective give their core away (several ranks share each core).
    env.setdefault("OMPI_MCA_mpi_yield_when_idle", "1")
    # A single-node run needs no network transports; keeps start-up fast and quiet.
    env.setdefault("OMPI_MCA_btl", "self,vader")
    env.setdefault("OMPI_MCA_btl_vader_single_copy_mechanism", "none")
    return env


def run(args, np=1, cwd=None, check=True, timeout=1800):
    """Runs `seam ARGS` on np ranks; returns (exit code, stdout, stderr)."""
    cmd = [SEAM] + list(args)
    if np > 1:
        cmd = [MPIEXEC, "--oversubscribe", "-np", str(np)] + cmd
    p = subprocess.run(cmd, cwd=cwd, env=mpi_env(), capture_output=True, text=True,
                       timeout=timeout)
    if check and p.returncode != 0:
        raise AssertionError("seam failed (%d): %s\nstdout:\n%s\nstderr:\n%s"
                             % (p.returncode, " ".join(cmd), p.stdout[-4000:], p.stderr[-4000:]))
    return p.returncode, p.stdout, p.stderr


def solve(yaml_path, np=1, extra=()):
    """Runs a case into a fresh temporary directory; returns the output directory."""
    out = tempfile.mkdtemp(prefix="seam_verif_")
    run(["run", yaml_path, "-o", out, "--quiet"] + list(extra), np=np)
    return out


def expect_input_error(what, work, name, line, must=(), timeout=300):
    """`seam check NAME` and `seam run NAME` in `work` both end with exit 1 and the message
    `seam: input error: NAME:LINE:` (any line if `line` is None) containing every piece of
    `must`."""
    for cmd in (["check", name], ["run", name, "-o", "out", "--quiet"]):
        code, out, err = run(cmd, cwd=work, check=False, timeout=timeout)
        if code != 1:
            raise AssertionError("%s: %s: exit %d, expected 1\n%s%s"
                                 % (what, cmd[0], code, out[-1500:], err[-1500:]))
        prefix = "seam: input error: %s:" % name + ("%d:" % line if line else "")
        if prefix not in err:
            raise AssertionError("%s: no located message %r:\n%s" % (what, prefix, err))
        for piece in must:
            if piece not in err:
                raise AssertionError("%s: message lacks %r:\n%s" % (what, piece, err))


def write_case(directory, name, text):
    path = os.path.join(directory, name)
    with open(path, "w") as f:
        f.write(text)
    return path


def read_csv(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    out = []
    for r in rows:
        conv = {}
        for k, v in r.items():
            try:
                conv[k] = float(v)
            except (TypeError, ValueError):
                conv[k] = v
        out.append(conv)
    return out


def read_json(path):
    with open(path) as f:
        return json.load(f)


def last_step_rows(rows):
    last = max(r["step"] for r in rows)
    return [r for r in rows if r["step"] == last]


def assert_close(actual, expected, rtol=0.0, atol=0.0, what="value"):
    if not (abs(actual - expected) <= atol + rtol * abs(expected)):
        raise AssertionError("%s: got %.17g, expected %.17g (|diff| = %.3e, rtol %.1e, atol %.1e)"
                             % (what, actual, expected, abs(actual - expected), rtol, atol))


def slope(h, e):
    """Least-squares slope of log e against log h."""
    lx = [math.log(v) for v in h]
    ly = [math.log(v) for v in e]
    mx = sum(lx) / len(lx)
    my = sum(ly) / len(ly)
    return sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sum((a - mx) ** 2 for a in lx)


def copy_example(name, yaml, replace=()):
    """A copy of examples/NAME in a new temporary folder, with text replacements (each must
    be found) in its input YAML; returns (folder, path of the YAML)."""
    work = tempfile.mkdtemp(prefix="seam_ex_")
    src = os.path.join(HERE, "..", "..", "examples", name)
    for f in os.listdir(src):
        shutil.copy(os.path.join(src, f), work)
    path = os.path.join(work, yaml)
    with open(path) as f:
        text = f.read()
    for a, b in replace:
        if a not in text:
            raise AssertionError("%s: '%s' not found" % (yaml, a))
        text = text.replace(a, b)
    with open(path, "w") as f:
        f.write(text)
    return work, path


def cleanup(*dirs):
    for d in dirs:
        shutil.rmtree(d, ignore_errors=True)


def main(tests):
    """Runs the given test functions; prints a summary line; exits non-zero on failure."""
    failed = 0
    for t in tests:
        start = time.monotonic()
        try:
            t()
            print("PASS %s (%.1f s)" % (t.__name__, time.monotonic() - start))
        except Exception as e:  # noqa: BLE001 - report every failure, keep going
            failed += 1
            print("FAIL %s (%.1f s)" % (t.__name__, time.monotonic() - start),
                  "\n   ", str(e).replace("\n", "\n    "))
    print("%d passed, %d failed" % (len(tests) - failed, failed))
    sys.stdout.flush()
    sys.exit(1 if failed else 0)


def full_only(test):
    """Runs `test` only with SEAM_FULL=1 (cases too slow for CI)."""
    @functools.wraps(test)
    def run():
        if not FULL:
            print("   skipped (set SEAM_FULL=1)")
            return
        test()
    return run
