"""Starts N ParaView probes at once (paraview_probe.py under pvpython, each in an Xvfb of its
own, one attempt each) for ROUNDS rounds and counts the failed window creations: the
reproduction of test_paraview's flake (virtual_display says why it happened).

    /usr/bin/python3 tests/verification/paraview_stress.py N ROUNDS [--reset]

--reset starts Xvfb as test_paraview did before (the server resets when its last client
disconnects). A two-step results.pvd of one quad is written to a temporary folder."""
import collections
import concurrent.futures
import os
import re
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import test_paraview as T  # noqa: E402

PIECE = """<?xml version="1.0"?>
<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian"><UnstructuredGrid>
<Piece NumberOfPoints="4" NumberOfCells="1">
<Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">
0 0 0 1 0 0 1 1 0 0 1 0</DataArray></Points>
<Cells><DataArray type="Int32" Name="connectivity" format="ascii">0 1 2 3</DataArray>
<DataArray type="Int32" Name="offsets" format="ascii">4</DataArray>
<DataArray type="UInt8" Name="types" format="ascii">9</DataArray></Cells>
<PointData><DataArray type="Float64" Name="f" format="ascii">0 1 2 3</DataArray></PointData>
</Piece></UnstructuredGrid></VTKFile>
"""
PVD = """<?xml version="1.0"?>
<VTKFile type="Collection" version="0.1"><Collection>
<DataSet timestep="0" file="piece.vtu"/><DataSet timestep="1" file="piece.vtu"/>
</Collection></VTKFile>
"""


def one(work, i, reset):
    server, display = T.virtual_display(reset=reset)
    if server is None:
        return "Xvfb did not start"
    try:
        p = subprocess.run([T.pvpython(), T.PROBE, os.path.join(work, "results.pvd"),
                            os.path.join(work, "p%d.png" % i), "f"], capture_output=True,
                           text=True, timeout=600, env=T.pvpython_env(display))
    finally:
        server.terminate()
        server.wait()
    if "PARAVIEW_REPORT" in p.stdout:
        return "ok"
    errors = [re.sub(r" \(0x\w+\)|DISPLAY=:\d+\. ", "", line.split("ERR|")[-1]).strip()[:90]
              for line in p.stderr.splitlines() if "ERR|" in line]
    return "exit %d: %s" % (p.returncode, errors[0] if errors else p.stderr[-200:])


def main():
    n, rounds, reset = int(sys.argv[1]), int(sys.argv[2]), "--reset" in sys.argv
    work = tempfile.mkdtemp(prefix="seam_paraview_stress_")
    T.H.write_case(work, "piece.vtu", PIECE)
    T.H.write_case(work, "results.pvd", PVD)
    failed = 0
    try:
        for r in range(rounds):
            start = time.monotonic()
            with concurrent.futures.ThreadPoolExecutor(n) as pool:
                results = list(pool.map(lambda i: one(work, i, reset), range(n)))
            bad = [x for x in results if x != "ok"]
            failed += len(bad)
            print("round %d: %d probes at once, %d failed (%.1f s, load %.1f)"
                  % (r + 1, n, len(bad), time.monotonic() - start, os.getloadavg()[0]))
            for what, count in collections.Counter(bad).items():
                print("   %d x %s" % (count, what))
    finally:
        T.H.cleanup(work)
    print("%s: %d of %d probes failed" % ("Xvfb resetting" if reset else "Xvfb -noreset",
                                          failed, n * rounds))
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
