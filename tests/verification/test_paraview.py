"""ParaView as the client (issue 17): results.pvd of a contact run and of a fluid-structure run,
opened by ParaView itself.

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
The Turek-Hron FSI1 flag (coarse, 2 load steps), serially and on 3 ranks: the fluid fields of
CONTRACT.md (velocity, pressure, mesh_displacement) and the displacement, vectors with 3
components, plausible ranges (check_fsi_report), the same ranges on 1 and 3 ranks, a PNG.

Skipped, with a message, only where pvpython is missing (scripts/install-deps.sh installs
python3-paraview and xvfb). Renders in an Xvfb server of its own, started by the test with
-noreset (virtual_display says why).
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


def virtual_display(reset=False):
    """Starts Xvfb (24-bit screen) on a free display number and returns (process, display)
    once the server accepts clients (-displayfd: Xvfb writes the number when it is ready), or
    (None, None) if it could not start.

    -noreset: by default an X server resets itself whenever its last client disconnects, and a
    client connecting during the reset is refused. pvpython connects and disconnects before it
    opens its window (hwloc, in MPI's start-up, looks for GPUs on displays :0 to :9 and on
    $DISPLAY; VTK queries the visuals on a connection of its own), so its window's
    XOpenDisplay raced with the reset: VTK's "bad X server connection" abort in CreateAWindow.
    8 probes started at once on a loaded machine, 3 rounds: 18 of 24 aborted without -noreset
    (13 of 16 with hwloc's search switched off alone), none with it (paraview_stress.py;
    reset=True starts the server as before, to reproduce it)."""
    r, w = os.pipe()
    try:
        proc = subprocess.Popen(["Xvfb", "-displayfd", str(w)] + ([] if reset else ["-noreset"])
                                + ["-screen", "0", "1280x1024x24", "-nolisten", "tcp"], pass_fds=(w,),
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


def pvpython_env(display):
    """pvpython's environment: the display, and no GPU search by hwloc on other X servers
    (it connects to displays :0 to :9, which may be another test's Xvfb or a user's screen)."""
    env = dict(os.environ, HWLOC_COMPONENTS="-gl")
    if display:
        env["DISPLAY"] = display
    return env


def probe(pvd, png, color):
    """Runs paraview_probe.py under pvpython: in a virtual X server of its own (Debian's
    ParaView has no offscreen rendering: --force-offscreen-rendering crashes it) with a 24-bit
    screen (the default 8-bit one has no OpenGL visual), started here and waited for before
    pvpython opens it; where Xvfb is missing, offscreen (other ParaView builds). A failed
    window creation is not retried: its cause was found (virtual_display) and must show."""
    if shutil.which("Xvfb"):
        server, display = virtual_display()
        if server is None:
            raise AssertionError("Xvfb did not start")
        command = [pvpython(), PROBE, pvd, png, color]
    else:
        server, display = None, None
        command = [pvpython(), "--force-offscreen-rendering", PROBE, pvd, png, color]
    try:
        p = subprocess.run(command, capture_output=True, text=True, timeout=600,
                           env=pvpython_env(display))
    finally:
        if server is not None:
            server.terminate()
            server.wait()
    for line in p.stdout.splitlines():
        if line.startswith("PARAVIEW_REPORT "):
            return json.loads(line[len("PARAVIEW_REPORT "):])
    # VTK's own messages (e.g. "bad X server connection", "Could not find a decent visual")
    # come before the stack trace that fills the end of stderr.
    messages = [line for line in p.stderr.splitlines()
                if "ERR" in line or "X server" in line or "visual" in line.lower()]
    raise AssertionError("pvpython could not read %s:\n%s (DISPLAY %s): exit %d\n%s\n%s\n%s"
                         % (pvd, " ".join(command), display, p.returncode,
                            "\n".join(messages[:10]), p.stdout[-1500:], p.stderr[-1500:]))


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


FSI_POINT_FIELDS = {"displacement": 3, "velocity": 3, "pressure": 1, "mesh_displacement": 3}


def fsi_run(np):
    """Turek-Hron FSI1 (examples/turek_hron/fsi1.yaml) on the coarse mesh of test_fsi.py
    (refine 0.5), its 2 load steps; returns the output directory."""
    import test_restart as TR
    work = tempfile.mkdtemp(prefix="seam_paraview_fsi_")
    H.write_case(work, "case.geo", TR.fsi_geo(0.5))
    path = H.write_case(work, "case.yaml", TR.fsi_yaml("fsi1.yaml", 100, ("steps: 2", "steps: 2")))
    out = H.solve(path, np=np)
    return work, out


def check_fsi_report(report, out, np):
    """A 2D fluid-structure run as ParaView sees it: both load steps, the fields of CONTRACT.md
    for fluid cells with 3-component vectors (ParaView warps by 3-vectors), velocities of the
    inflow's size (mean 0.2, peak 0.3 at the inlet, faster beside the cylinder), the
    displacement's largest size that of the flag's tip in probes.csv, the mesh displacement
    within it, a pressure that rises ahead of the cylinder."""
    where = "FSI np = %d" % np
    if [round(t, 12) for t in report["times"]] != [0.5, 1.0]:
        raise AssertionError("%s: time steps %s, expected [0.5, 1]" % (where, report["times"]))
    pts = report["points"]
    for name, n in FSI_POINT_FIELDS.items():
        if name not in pts:
            raise AssertionError("%s: ParaView finds no point field %r (it has %s)"
                                 % (where, name, sorted(pts)))
        if pts[name]["components"] != n:
            raise AssertionError("%s: %r has %d components, expected %d"
                                 % (where, name, pts[name]["components"], n))
    for name in ("displacement", "velocity", "mesh_displacement"):
        if pts[name]["ranges"][2] != [0.0, 0.0]:
            raise AssertionError("%s: %s has a z component %s in 2D" % (where, name,
                                                                     pts[name]["ranges"][2]))
    speed = pts["velocity"]["magnitude"][1]
    if not 0.3 <= speed <= 0.6:
        raise AssertionError("%s: largest |velocity| %.4g, expected 0.3 .. 0.6" % (where, speed))
    tip = H.read_csv(os.path.join(out, "probes.csv"))[-1]
    tip_u = math.hypot(tip["ux"], tip["uy"])
    largest = pts["displacement"]["magnitude"][1]
    if not tip_u <= largest <= 1.1 * tip_u:
        raise AssertionError("%s: largest |displacement| %.4g, the flag's tip moved %.4g"
                             % (where, largest, tip_u))
    if pts["mesh_displacement"]["magnitude"][1] > largest * (1 + 1e-12):
        raise AssertionError("%s: the fluid mesh moves more than the flag" % where)
    low, high = pts["pressure"]["ranges"][0]
    if not (high > 10.0 and low < high / 10.0):
        raise AssertionError("%s: pressure in [%.4g, %.4g]" % (where, low, high))
    image = report["image"]
    if image["size"] != [800, 600] or image["colours"] < 20:
        raise AssertionError("%s: the rendered image is %s with %d colours"
                             % (where, image["size"], image["colours"]))
    print("   %s: %d points, %d cells; max |v| %.4f, pressure in [%.3f, %.3f], max |u| %.4e "
          "(tip %.4e); PNG with %d colours" % (where, report["n_points"], report["n_cells"],
                                               speed, low, high, largest, tip_u,
                                               image["colours"]))


def test_paraview_reads_fsi_results():
    """results.pvd of a fluid-structure run (FSI1, coarse), serially and on 3 ranks."""
    if not pvpython():
        print("   SKIPPED: pvpython not found (install python3-paraview: scripts/install-deps.sh)")
        return
    dirs, reports = [], {}
    try:
        for np in (1, 3):
            work, out = fsi_run(np)
            dirs += [work, out]
            png = os.path.join(work, "fsi1_np%d.png" % np)
            reports[np] = probe(os.path.join(out, "results.pvd"), png, "velocity")
            check_fsi_report(reports[np], out, np)
            if KEEP:
                shutil.copy(png, KEEP)
        for name in FSI_POINT_FIELDS:
            for x, y in zip(reports[1]["points"][name]["magnitude"],
                            reports[3]["points"][name]["magnitude"]):
                H.assert_close(y, x, rtol=1e-6, atol=1e-12,
                               what="range of |%s|, np = 3 vs np = 1" % name)
    finally:
        H.cleanup(*dirs)


if __name__ == "__main__":
    H.main([test_paraview_reads_contact_results, test_paraview_reads_fsi_results])
