#!/bin/sh
# Installs GetFEM's Python interface (Debian's python3-getfem, GetFEM 5.4 on bookworm, built
# with MUMPS) for /usr/bin/python3, and checks that it imports.
#   sh bench/peers/getfem/setup.sh
# Not part of `make test`: it needs root for apt-get and the network.
set -eu
if ! /usr/bin/python3 -c "import getfem" 2>/dev/null; then
  apt-get update
  DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends python3-getfem
fi
/usr/bin/python3 -c "import getfem" && dpkg-query -W python3-getfem
