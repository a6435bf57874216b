#!/usr/bin/env bash
# Installs the Debian packages seam needs, only those that are missing.
set -euo pipefail
packages=(
  build-essential cmake ninja-build ccache pkg-config git
  petsc-dev libopenblas0-pthread
  libeigen3-dev libgmsh-dev gmsh libmetis-dev libscotch-dev libyaml-cpp-dev libmuparser-dev
  libcli11-dev libspdlog-dev libcgal-dev
  googletest libgtest-dev libbenchmark-dev
  python3 python3-matplotlib python3-numpy
  python3-paraview xvfb
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "seam: installing missing packages: ${missing[*]}"
  SUDO=""
  [[ $(id -u) -ne 0 ]] && SUDO=sudo
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
