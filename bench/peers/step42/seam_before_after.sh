#!/bin/sh
# seam's CPU time on the step-42 problem (compare.py's mesh and input) with two seam binaries,
# run one after the other on the same input: a reference build ("before", by default the main
# checkout's) and the current one ("after"). Prints per run the CPU seconds (user + system of
# the process, from /usr/bin/time, which a shared machine inflates less than wall time), Newton
# iterations, active nodes and contact force, then the ratio after / before of the smallest
# CPU time of each binary.
#   sh bench/peers/step42/seam_before_after.sh [n, default 32] [repeats, default 1] \
#       before-binary [after, default build/bin/seam] [linear]
# `linear` (default iterative) is the solver.linear of the input.
set -eu
n=${1:-32}
repeats=${2:-1}
before=${3:-}
if [ -z "$before" ] || [ ! -x "$before" ]; then
  echo "usage: $0 n repeats BEFORE_SEAM [AFTER_SEAM] [linear]: BEFORE_SEAM must be a seam binary (e.g. a build of an earlier commit)" >&2
  exit 1
fi
after=${4:-build/bin/seam}
linear=${5:-iterative}
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/seam_step42_XXXXXX")
trap 'rm -rf "$work"' EXIT
python3 - "$here" "$work" "$n" "$linear" <<'PY'
import os, sys
sys.path.insert(0, sys.argv[1])
import compare
work, n, linear = sys.argv[2], int(sys.argv[3]), sys.argv[4]
open(os.path.join(work, "cube.geo"), "w").write(compare.GEO.format(nodes=n + 1))
open(os.path.join(work, "cube.yaml"), "w").write(
    compare.YAML.format(n=n, linear="  linear: %s\n" % linear))
PY
for k in $(seq "$repeats"); do
  for which in before after; do
    eval exe=\$$which
    out="$work/out_${which}_$k"
    /usr/bin/time -f "%U %S" -o "$work/time_${which}_$k" \
      env OMP_NUM_THREADS=1 "$exe" run "$work/cube.yaml" -o "$out" --quiet
  done
done
python3 - "$work" "$repeats" "$before" "$after" <<'PY'
import csv, os, sys
work, repeats = sys.argv[1], int(sys.argv[2])
best = {}
for k in range(1, repeats + 1):
    for which, exe in (("before", sys.argv[3]), ("after", sys.argv[4])):
        user, system = map(float, open(os.path.join(work, "time_%s_%d" % (which, k))).read()
                           .split()[-2:])
        out = os.path.join(work, "out_%s_%d" % (which, k))
        step = list(csv.DictReader(open(os.path.join(out, "steps.csv"))))[-1]
        itf = list(csv.DictReader(open(os.path.join(out, "interfaces.csv"))))[-1]
        cpu = user + system
        best[which] = min(best.get(which, cpu), cpu)
        print("%-6s %-40s CPU %7.2f s  Newton %s  active %s  force %.10f"
              % (which, exe, cpu, step["newton_iterations"], itf["active_nodes"],
                 float(itf["normal_force"])))
print("CPU after / before (smallest of %d): %.2f / %.2f = %.3f"
      % (repeats, best["after"], best["before"], best["after"] / best["before"]))
PY
