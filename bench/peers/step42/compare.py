#!/usr/bin/env python3
"""seam against deal.II step-42 on the same problem (issue 16, benchmark 1), side by side.

The problem (step-42, made purely elastic): the unit cube of Q1 / hex8 cells (n^3, n = 16,
32, 64: step-42's 4, 5, 6 global refinements), E = 2e5, nu = 0.3, bottom clamped, sides free
only in z, indented by the rigid sphere of radius 0.6 centred at (0.5, 0.5, 1.59) (0.01 into
the top), in one load step.

  step-42: its own input (p*.prm) with "yield stress = 1e10", obstacle sphere, global
           refinement, one cycle; primal-dual active set, BiCGStab + Trilinos ML (AMG),
           DEAL_II_NUM_THREADS=1 (one core, as seam on one rank).
  seam:    the same mesh from gmsh (transfinite hexahedra), linear_elastic, the rigid_sphere,
           one static step, `linear` as chosen (--linear, default: seam's default).

Both codes write their graphical output once; the wall and CPU times (user + system) are those
of the whole processes (mesh generation, set-up, solve and output included) measured here, and
the codes' own totals; "asm" and "solve" are the CPU seconds of each code's own timers
(step-42's TimerOutput sections "Assembling" and "Solve", seam's summary.json cpu_timings
"assembly" and "linear_solve"; seam's "condensation" of the contact constraints is separate).

  python3 bench/peers/step42/compare.py --step42 build/peers/step42/step-42 \\
      --seam build/bin/seam [--sizes 16 32] [--linear direct|iterative|auto] [--np 1]

bench/peers/step42/setup.sh installs and builds step-42 first.
"""
import argparse
import csv
import json
import os
import resource
import re
import subprocess
import sys
import tempfile
import time

REFINEMENTS = {8: 3, 16: 4, 32: 5, 64: 6}

PRM = """set polynomial degree             = 1
set number of initial refinements = {refinements}
set number of cycles              = 1
set refinement strategy           = global
set obstacle                      = sphere
set output directory              = {out}
set transfer solution             = false
set base mesh                     = box
set yield stress                  = 1e10
"""

GEO = """SetFactory("OpenCASCADE");
Box(1) = {{0, 0, 0, 1, 1, 1}};
Transfinite Curve{{:}} = {nodes};
Transfinite Surface{{:}}; Recombine Surface{{:}}; Transfinite Volume{{1}};
Physical Surface("sides") = {{1, 2, 3, 4}};
Physical Surface("bottom") = {{5}};
Physical Surface("top") = {{6}};
Physical Volume("cube") = {{1}};
"""

YAML = """title: step-42 made elastic, {n}^3 hex8
dimension: 3
mesh: {{geo: cube.geo}}
materials:
  steel: {{model: linear_elastic, young: 2.0e5, poisson: 0.3}}
bodies:
  - {{region: cube, material: steel}}
boundary_conditions:
  - {{region: bottom, type: dirichlet, components: [x, y, z], value: [0, 0, 0]}}
  - {{region: sides, type: dirichlet, components: [x, y], value: [0, 0]}}
interfaces:
  - name: indenter
    type: contact
    slave: top
    rigid_sphere: {{center: [0.5, 0.5, 1.59], radius: 0.6}}
time: {{integrator: static, end: 1, steps: 1}}
solver:
  newton: {{tolerance: 1.0e-10, max_iterations: 30}}
{linear}"""


def mpi_env():
    env = dict(os.environ)
    env.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
    env.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    env.setdefault("OMPI_MCA_rmaps_base_oversubscribe", "1")
    env["DEAL_II_NUM_THREADS"] = "1"
    env["OMP_NUM_THREADS"] = "1"
    return env


def children_cpu():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def timed(cmd, cwd):
    start, cpu = time.perf_counter(), children_cpu()
    p = subprocess.run(cmd, cwd=cwd, env=mpi_env(), capture_output=True, text=True)
    wall = time.perf_counter() - start
    cpu = children_cpu() - cpu
    if p.returncode != 0:
        sys.exit("failed (%d): %s\n%s\n%s" % (p.returncode, " ".join(cmd), p.stdout[-3000:],
                                              p.stderr[-3000:]))
    return p.stdout, wall, cpu


def timer_sections(text, title):
    """Seconds per section of the deal.II TimerOutput table headed by `title`."""
    at = text.find(title)
    if at < 0:
        return {}
    end = text.find("Total ", at + len(title))
    out = {}
    for line in text[at:end if end > 0 else len(text)].splitlines():
        m = re.match(r"\|\s*([^|]*?)\s*\|\s*\d+\s*\|\s*([0-9.e+-]+)s\s*\|", line)
        if m:
            out[m.group(1)] = float(m.group(2))
    return out


def run_step42(exe, n, np, work):
    prm = os.path.join(work, "step42_%d.prm" % n)
    out = os.path.join(work, "step42_%d" % n)
    os.makedirs(out, exist_ok=True)
    with open(prm, "w") as f:
        f.write(PRM.format(refinements=REFINEMENTS[n], out=out))
    cmd = [exe, prm]
    if np > 1:
        cmd = ["mpirun", "-np", str(np)] + cmd
    text, wall, cpu = timed(cmd, work)
    with open(os.path.join(work, "step42_%d.log" % n), "w") as f:
        f.write(text)
    newton = len(re.findall(r"Newton iteration \d+", text))
    active = [int(v) for v in re.findall(r"Size of active set: (\d+)", text)]
    sections = timer_sections(text, "Total CPU time elapsed since start")
    return {
        "dofs": int(re.search(r"Number of degrees of freedom: (\d+)", text).group(1)),
        "newton": newton,
        "active": active[-1] if active else 0,
        "force": float(re.search(r"Contact force = (\S+)", text).group(1)),
        "own_total": float(re.search(r"Total wallclock time elapsed since start\s*\|\s*(\S+)s",
                                     text).group(1)),
        "wall": wall,
        "cpu": cpu,
        "asm": sections.get("Assembling", float("nan")),
        "solve": sections.get("Solve", float("nan")),
    }


def run_seam(exe, n, np, linear, work):
    case = os.path.join(work, "seam_%d" % n)
    os.makedirs(case, exist_ok=True)
    with open(os.path.join(case, "cube.geo"), "w") as f:
        f.write(GEO.format(nodes=n + 1))
    with open(os.path.join(case, "cube.yaml"), "w") as f:
        f.write(YAML.format(n=n, linear="  linear: %s\n" % linear if linear else ""))
    out = os.path.join(case, "out")
    cmd = [exe, "run", os.path.join(case, "cube.yaml"), "-o", out, "--quiet"]
    if np > 1:
        cmd = ["mpirun", "-np", str(np)] + cmd
    _, wall, cpu = timed(cmd, case)
    summary = json.load(open(os.path.join(out, "summary.json")))
    step = list(csv.DictReader(open(os.path.join(out, "steps.csv"))))[-1]
    itf = list(csv.DictReader(open(os.path.join(out, "interfaces.csv"))))[-1]
    return {
        "dofs": int(summary["dofs"]),
        "newton": int(step["newton_iterations"]),
        "active": int(step["active_nodes"]),
        "force": float(itf["normal_force"]),
        "own_total": float(summary["wall_seconds"]),
        "wall": wall,
        "cpu": cpu,
        "asm": summary.get("cpu_timings", {}).get("assembly", float("nan")),
        "solve": summary.get("cpu_timings", {}).get("linear_solve", float("nan")),
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--step42", default="build/peers/step42/step-42")
    ap.add_argument("--seam", default="build/bin/seam")
    ap.add_argument("--sizes", type=int, nargs="+", default=[16, 32])
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--linear", default="", help="seam's solver.linear (default: seam's)")
    ap.add_argument("--work", default="", help="directory for the runs (default: temporary)")
    args = ap.parse_args()
    work = os.path.abspath(args.work or tempfile.mkdtemp(prefix="step42_vs_seam_"))
    os.makedirs(work, exist_ok=True)
    step42, seam = os.path.abspath(args.step42), os.path.abspath(args.seam)
    print("runs in %s; np = %d; seam linear: %s" % (work, args.np, args.linear or "default"))
    header = ("%-6s %-8s %9s %7s %7s %12s %9s %9s %9s %9s %9s"
              % ("mesh", "code", "dofs", "newton", "active", "force", "wall [s]", "own [s]",
                 "CPU [s]", "asm CPU", "solve CPU"))
    print(header)
    for n in args.sizes:
        d = run_step42(step42, n, args.np, work)
        s = run_seam(seam, n, args.np, args.linear, work)
        for name, r in (("step-42", d), ("seam", s)):
            print("%-6s %-8s %9d %7d %7d %12.6g %9.2f %9.2f %9.2f %9.2f %9.2f"
                  % ("%d^3" % n, name, r["dofs"], r["newton"], r["active"], r["force"],
                     r["wall"], r["own_total"], r["cpu"], r["asm"], r["solve"]))
        print("%-6s %-8s %9s %7.2f %7.2f %12.4f %9.3f %9.3f %9.3f %9.3f %9.3f"
              % ("%d^3" % n, "ratio", "", s["newton"] / max(d["newton"], 1),
                 s["active"] / max(d["active"], 1), s["force"] / d["force"],
                 s["wall"] / d["wall"], s["own_total"] / d["own_total"], s["cpu"] / d["cpu"],
                 s["asm"] / d["asm"], s["solve"] / d["solve"]))
        sys.stdout.flush()


if __name__ == "__main__":
    main()
