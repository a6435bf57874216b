"""Surface nodes of a ring that lie inside a cell of another ring, per output file.

    /usr/bin/python3 examples/rings/inside_other_ring.py out/results_00210.vtu ...

Reads seam's binary .vtu (Points are the deformed positions, quad4 cells), finds the rings as
the connected groups of cells and the surface nodes as the nodes of edges of one cell, and
counts the surface nodes inside a quad of another ring, with the deepest (the distance to the
nearest edge of that quad). The files carry no self-contact roles, so slave and master nodes
are counted together."""
import base64
import re
import struct
import sys
from collections import Counter

import numpy as np

TYPES = {"Float64": "<f8", "Int32": "<i4", "Int64": "<i8", "UInt8": "u1"}


def arrays(path):
    text = open(path).read()
    out = {}
    for m in re.finditer(r'<DataArray type="(\w+)" Name="(\w+)"(?: NumberOfComponents="(\d+)")?'
                         r'[^>]*>\s*(\S+)\s*</DataArray>', text):
        kind, name, components, data = m.groups()
        raw = base64.b64decode(data)
        n = struct.unpack("<Q", raw[:8])[0]
        a = np.frombuffer(raw[8:8 + n], dtype=TYPES[kind])
        out[name] = a.reshape(-1, int(components)) if components else a
    return out


def rings(cells, n):
    """The ring of each of the n nodes: the connected groups of `cells`, numbered 0, 1, ... by
    their lowest node."""
    parent = np.arange(n)

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for c in cells:
        roots = [find(i) for i in c]
        for r in roots[1:]:
            parent[r] = roots[0]
    roots = np.array([find(i) for i in range(n)])
    return np.unique(roots, return_inverse=True)[1]


def inside_other_ring(path):
    a = arrays(path)
    x = a["Points"][:, :2]
    cells = a["connectivity"].reshape(-1, 4)
    ring = rings(cells, len(x))
    cell_ring = ring[cells[:, 0]]
    edges = Counter(tuple(sorted((c[k], c[(k + 1) % 4]))) for c in cells for k in range(4))
    surface = sorted({i for e, n in edges.items() if n == 1 for i in e})
    quads = x[cells]
    lo, hi = quads.min(1), quads.max(1)
    count, deepest = 0, 0.0
    for i in surface:
        p = x[i]
        near = np.where((cell_ring != ring[i]) & (lo[:, 0] <= p[0]) & (hi[:, 0] >= p[0]) &
                        (lo[:, 1] <= p[1]) & (hi[:, 1] >= p[1]))[0]
        for c in near:
            q = quads[c]
            e = np.roll(q, -1, 0) - q
            d = p - q
            cross = e[:, 0] * d[:, 1] - e[:, 1] * d[:, 0]
            if (cross >= 0).all() or (cross <= 0).all():
                t = np.clip((d * e).sum(1) / (e * e).sum(1), 0.0, 1.0)
                depth = np.sqrt(((d - t[:, None] * e) ** 2).sum(1)).min()
                count, deepest = count + 1, max(deepest, depth)
                break
    return a["TimeValue"][0], len(surface), count, deepest


if __name__ == "__main__":
    for path in sys.argv[1:]:
        t, n, count, deepest = inside_other_ring(path)
        print("%s  t = %.5f  surface nodes %d, inside another ring %d (deepest %.2e)"
              % (path, t, n, count, deepest))
