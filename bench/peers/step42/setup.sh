#!/bin/sh
# Installs deal.II (Debian's libdeal.ii-dev and libdeal.ii-doc), copies its step-42 example,
# makes the yield stress a run-time parameter ("yield stress", default 400 as in step-42) so
# that a value of 1e10 keeps it purely elastic, makes its timer report CPU beside wall times,
# and builds it in release mode.
#   sh bench/peers/step42/setup.sh [build directory, default build/peers/step42]
# Not part of `make test`: it needs root for apt-get and the network.
set -eu
out=${1:-build/peers/step42}
examples=/usr/share/doc/libdeal.ii-doc/examples/step-42
if [ ! -f "$examples/step-42.cc" ]; then
  apt-get update
  DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends libdeal.ii-dev \
    libdeal.ii-doc
fi
mkdir -p "$out"
cp "$examples/step-42.cc" "$examples/CMakeLists.txt" "$out/"
python3 - "$out/step-42.cc" <<'PY'
import sys
path = sys.argv[1]
text = open(path).read()
edits = [
    (', sigma_0(400.0)', ', sigma_0(prm.get_double("yield stress"))'),
    ('    prm.declare_entry("base mesh",',
     '    prm.declare_entry("yield stress", "400", Patterns::Double(),\n'
     '                      "Initial yield stress sigma_0 (1e10: purely elastic).");\n'
     '    prm.declare_entry("base mesh",'),
    # CPU times of its sections beside the wall times (a shared machine inflates wall time).
    ('                      TimerOutput::wall_times)',
     '                      TimerOutput::cpu_and_wall_times)'),
]
for old, new in edits:
    if text.count(old) != 1:
        sys.exit("step-42.cc: cannot patch '%s' (another deal.II version?)" % old)
    text = text.replace(old, new)
open(path, "w").write(text)
PY
cd "$out"
cmake -DCMAKE_BUILD_TYPE=Release . > cmake.log
make -j 2 > make.log
echo "built $out/step-42"
