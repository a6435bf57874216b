"""ParaView as the client (issue 17): results.pvd of a contact run, opened by ParaView itself.

examples/hertz_2d on its coarse CI mesh, serially and on 3 ranks (.vtu and .pvtu pieces): pvpython
(Debian's python3-paraview) reads results.pvd through its PVD reader (paraview_probe.py) and
must find
  * every time step (t = 0 and the 5 load steps);
  * every point field of CONTRACT.md with its number of components: displacement 3, velocity 3,
    lagrange_multiplier 3, weighted_gap 1, contact_status 1; and every cell field:
    cauchy_stress 6, von_mises 1, rank 1, material 1;
  * plausible values at t = 1: the cylinder moved down by about the prescribed 0.02 at most
    (0.021) and never up, no velocity (static), contact status only -1 (off the interface), 0 (inactive)
    and 2 (slip) with some nodes in contact, no weighted gap below -1e-12 (no penetration), the
    largest multiplier within 15 % of Hertz's peak pressure p0 = sqrt(F E* / (pi R)) for the
    measured load F (traction per current length, coarse mesh), von Mises stress
    between 0.3 p0 and 1.2 p0 (Johnson: max 0.56 p0 below the surface in plane strain, higher
    where the quads are coarse), one material, rank 0 serially and 0..2 on 3 ranks;
  * the same numbers of cells serially and on 3 ranks, and the same ranges of the fields;
and it renders the last step (mesh and von Mises stress) to a PNG that is not blank.

Skipped, with a message, only where pvpython is missing (scripts/install-deps.sh installs
python3-paraview and xvfb). Renders in an Xvfb server started by the test.
"""
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import contact_analysis as C  # noqa: E402
import harness as H  # noqa: E402
import test_contact as TC  # noqa: E402

PROBE = os.path.join(H.HERE, "paraview_probe.py")
POINT_FIELDS = {"displacement": 3, "velocity": 3, "lagrange_multiplier": 3, "weighted_gap": 1,
                "contact_status": 1}
CELL_FIELDS = {"cauchy_stress": 6, "von_mises": 1, "rank": 1, "material": 1}
KEEP = os.environ.get("SEAM_PARAVIEW_IMAGES")  # a folder to keep the PNGs in


def pvpython():
    return shutil.which("pvpython")


def virtual_display():
    """Starts Xvfb (24-bit screen) on a free display number and returns (process, display)
    once the server accepts clients (-displayfd: Xvfb writes the number when it is ready), or
    (None, None) if it could not start."""
    r, w = os.pipe()
    try:
        proc = subprocess.Popen(["Xvfb", "-displayfd", str(w), "-screen", "0", "1280x1024x24",
                                 "-nolisten", "tcp"], pass_fds=(w,),
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    except OSError:
        os.close(r)
        os.close(w)
        return None, None
    os.close(w)
    with os.fdopen(r) as f:
        number = f.readline().strip()
    if not number:
        proc.kill()
        proc.wait()
        return None, None
    return proc, ":" + number


def probe(pvd, png, color):
    """Runs paraview_probe.py under pvpython: in a virtual X server (Debian's ParaView has no
    offscreen rendering: --force-offscreen-rendering crashes it) with a 24-bit screen (the
    default 8-bit one has no OpenGL visual), started here and waited for before pvpython
    opens it (xvfb-run -a raced on a loaded machine), up to three times, else offscreen
    (other ParaView builds)."""
    command = [pvpython(), PROBE, pvd, png, color]
    attempts = [None] * 3 if shutil.which("Xvfb") else []
    attempts.append([pvpython(), "--force-offscreen-rendering", PROBE, pvd, png, color])
    errors = []
    for cmd in attempts:
        server, env = None, None
        if cmd is None:
            server, display = virtual_display()
            if server is None:
                errors.append("Xvfb did not start")
                continue
            env = dict(os.environ, DISPLAY=display)
            cmd = command
        try:
            p = subprocess.run(cmd, capture_output=True, text=True, timeout=600, env=env)
        finally:
            if server is not None:
                server.terminate()
                server.wait()
        for line in p.stdout.splitlines():
            if line.startswith("PARAVIEW_REPORT "):
                return json.loads(line[len("PARAVIEW_REPORT "):])
        errors.append("%s (DISPLAY %s): exit %d\n%s\n%s"
                      % (" ".join(cmd), env["DISPLAY"] if env else "none", p.returncode,
                         p.stdout[-1500:], p.stderr[-1500:]))
    raise AssertionError("pvpython could not read %s:\n%s" % (pvd, "\n".join(errors)))


def check_report(report, out, np):
    where = "np = %d" % np
    times = report["times"]
    expected = [0.0, 0.2, 0.4, 0.6, 0.8, 1.0]
    if len(times) != len(expected) or max(abs(a - b) for a, b in zip(times, expected)) > 1e-12:
        raise AssertionError("%s: time steps %s, expected %s" % (where, times, expected))
    for kind, fields in (("points", POINT_FIELDS), ("cells", CELL_FIELDS)):
        for name, n in fields.items():
            if name not in report[kind]:
                raise AssertionError("%s: ParaView finds no %s field %r (it has %s)"
                                     % (where, kind[:-1], name, sorted(report[kind])))
            if report[kind][name]["components"] != n:
                raise AssertionError("%s: %r has %d components, expected %d"
                                     % (where, name, report[kind][name]["components"], n))
    pts, cells = report["points"], report["cells"]

    def within(name, low, high, values):
        lo, hi = values
        if not (low <= lo and hi <= high):
            raise AssertionError("%s: %s ranges over [%.6g, %.6g], expected within [%.6g, %.6g]"
                                 % (where, name, lo, hi, low, high))

    # The cut moves down by 0.02; the rim below it, pushed outwards, a little more.
    within("displacement y", -0.021, 1e-12, pts["displacement"]["ranges"][1])
    within("displacement x", -0.02, 0.02, pts["displacement"]["ranges"][0])
    within("|velocity|", 0.0, 0.0, pts["velocity"]["magnitude"])
    within("contact_status", -1, 2, pts["contact_status"]["ranges"][0])
    if pts["contact_status"]["ranges"][0][1] != 2:
        raise AssertionError("%s: no node in contact (contact_status never 2)" % where)
    within("weighted_gap", -1e-12, 1.0, pts["weighted_gap"]["ranges"][0])
    # Hertz with the measured load: F per unit length = 2 x the reaction of the cut (half model).
    estar = 1.0 / (1.0 - 0.3 ** 2)
    force = 2.0 * abs(C.reaction(out, "top", 1))
    p0 = math.sqrt(force * estar / math.pi)
    lam = pts["lagrange_multiplier"]["magnitude"][1]
    if abs(lam - p0) > 0.15 * p0:
        raise AssertionError("%s: largest multiplier %.6g, Hertz p0 %.6g" % (where, lam, p0))
    within("von_mises", 0.0, 1.2 * p0, cells["von_mises"]["ranges"][0])
    if cells["von_mises"]["ranges"][0][1] < 0.3 * p0:
        raise AssertionError("%s: von Mises at most %.3g, less than 0.3 p0" % (where, p0))
    within("material", 0, 0, cells["material"]["ranges"][0])
    within("rank", 0, np - 1, cells["rank"]["ranges"][0])
    if cells["rank"]["ranges"][0][1] != np - 1:
        raise AssertionError("%s: the rank field never reaches %d" % (where, np - 1))
    image = report["image"]
    if image["size"] != [800, 600] or image["colours"] < 20:
        raise AssertionError("%s: the rendered image is %s with %d colours"
                             % (where, image["size"], image["colours"]))
    print("   %s: %d points, %d cells, %d time steps; max |lambda| %.5f (Hertz p0 %.5f), "
          "max von Mises %.5f, u_y in [%.5f, %.5f]; PNG %dx%d with %d colours"
          % (where, report["n_points"], report["n_cells"], len(times), lam, p0,
             cells["von_mises"]["ranges"][0][1], pts["displacement"]["ranges"][1][0],
             pts["displacement"]["ranges"][1][1], image["size"][0], image["size"][1],
             image["colours"]))


def test_paraview_reads_contact_results():
    if not pvpython():
        print("   SKIPPED: pvpython not found (install python3-paraview: scripts/install-deps.sh)")
        return
    reports = {}
    work = tempfile.mkdtemp(prefix="seam_paraview_")
    try:
        for np in (1, 3):
            out, _ = TC.example_run("hertz_2d", "hertz_2d.yaml", "cylinder.geo", TC.COARSE_2D,
                                    np=np)
            png = os.path.join(work, "hertz_2d_np%d.png" % np)
            reports[np] = probe(os.path.join(out, "results.pvd"), png, "von_mises")
            check_report(reports[np], out, np)
            if KEEP:
                shutil.copy(png, KEEP)
        one, three = reports[1], reports[3]
        if one["n_cells"] != three["n_cells"]:
            raise AssertionError("cells: %d serially, %d on 3 ranks"
                                 % (one["n_cells"], three["n_cells"]))
        for kind in ("points", "cells"):
            for name in one[kind]:
                if name == "rank":
                    continue
                a, b = one[kind][name]["magnitude"], three[kind][name]["magnitude"]
                for x, y in zip(a, b):
                    H.assert_close(y, x, rtol=1e-6, atol=1e-12,
                                   what="range of |%s|, np = 3 vs np = 1" % name)
    finally:
        H.cleanup(work)
        TC.cleanup_runs()


if __name__ == "__main__":
    H.main([test_paraview_reads_contact_results])
