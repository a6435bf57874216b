#!/usr/bin/env python3
"""Where PCD's time per Newton iteration goes on the DFG 2D-1 levels (docs/fluid.md, "PCD's cost
on the finest mesh"): writes the last Newton Jacobian of each level's PCD run (the example's
geometry with (h, hc) = (0.08, 0.012) / 2^k, as bench/dfg_benchmark.py meshes it; PETSc's
`-ksp_view_mat binary:` through PETSC_OPTIONS), then times, in one process over all levels,
a plain MatMult on the velocity block and BoomerAMG's set-up and V-cycle on it, per nonzero,
with the memory hierarchy's probes (`seam-bench velocity_amg`: --stream, --copies, --rcm).

Usage: /usr/bin/python3 bench/pcd_cost.py [--levels 0,1,2,3] [--seam build/bin/seam]
           [--bench build/bin/seam-bench] [--keep DIR] [-- seam-bench velocity_amg options]
e.g. `-- --copies 4 --rcm --stream` or
`-- --setting 'default' --setting 'P_max 4|-u_pc_hypre_boomeramg_P_max 4'`.
"""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import dfg_benchmark  # noqa: E402  (level_folder, EXAMPLE)


def write_jacobian(seam, level, path):
    folder = dfg_benchmark.level_folder(level)
    with open(os.path.join(dfg_benchmark.EXAMPLE, "dfg_2d1.yaml")) as f:
        yaml = f.read() + "solver: {linear: iterative}\n"
    with open(os.path.join(folder, "case.yaml"), "w") as f:
        f.write(yaml)
    # Every Newton step writes its system to the same file: the last one stays.
    env = dict(os.environ, PETSC_OPTIONS="-ksp_view_mat binary:%s" % path)
    subprocess.run([seam, "run", os.path.join(folder, "case.yaml"), "-o",
                    os.path.join(folder, "out"), "--quiet", "--", "-fluid_schur", "pcd"],
                   env=env, check=True)
    shutil.rmtree(folder)


def main():
    argv = sys.argv[1:]
    extra = []
    if "--" in argv:
        extra = argv[argv.index("--") + 1:]
        argv = argv[:argv.index("--")]
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--levels", default="0,1,2,3")
    parser.add_argument("--seam", default=os.path.join(HERE, "..", "build", "bin", "seam"))
    parser.add_argument("--bench", default=os.path.join(HERE, "..", "build", "bin", "seam-bench"))
    parser.add_argument("--keep", help="folder for the matrices (kept; reused when present)")
    args = parser.parse_args(argv)
    folder = args.keep or tempfile.mkdtemp(prefix="seam_pcd_cost_")
    os.makedirs(folder, exist_ok=True)
    files = []
    for level in [int(k) for k in args.levels.split(",")]:
        path = os.path.join(folder, "J%d.bin" % level)
        if not os.path.exists(path):
            write_jacobian(args.seam, level, path)
        files.append(path)
    print("load average %.2f %.2f %.2f" % os.getloadavg(), flush=True)
    subprocess.run([args.bench, "velocity_amg"] + files + extra, check=True)
    print("load average %.2f %.2f %.2f" % os.getloadavg(), flush=True)
    if not args.keep:
        shutil.rmtree(folder)


if __name__ == "__main__":
    main()
