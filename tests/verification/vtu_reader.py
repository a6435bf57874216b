"""A reader for the VTU pieces seam writes (inline base64 "binary" data with a UInt64 byte
count, or ascii), without numpy: points, cells (the nodes of each, in VTK order) and the point
and cell fields, as plain lists. A .pvtu is read as the list of its pieces."""
import base64
import os
import struct
import xml.etree.ElementTree as ET

_FORMATS = {"Float64": "d", "Float32": "f", "Int32": "i", "Int64": "q", "UInt8": "B",
            "UInt32": "I", "UInt64": "Q"}


def _values(array):
    code = _FORMATS[array.get("type")]
    text = (array.text or "").strip()
    if array.get("format") == "ascii":
        cast = float if code in "df" else int
        return [cast(v) for v in text.split()]
    raw = base64.b64decode("".join(text.split()))
    n_bytes = struct.unpack("<Q", raw[:8])[0]
    size = struct.calcsize(code)
    return list(struct.unpack("<%d%s" % (n_bytes // size, code), raw[8:8 + n_bytes]))


def _grouped(array, values):
    n = int(array.get("NumberOfComponents", "1"))
    return values if n == 1 else [tuple(values[i:i + n]) for i in range(0, len(values), n)]


def read_piece(path):
    """{'points': [(x, y, z)], 'cells': [[point indices]], 'point_data': {name: list},
    'cell_data': {name: list}} of one .vtu file."""
    piece = ET.parse(path).getroot().find("UnstructuredGrid/Piece")
    points = _grouped(piece.find("Points/DataArray"), _values(piece.find("Points/DataArray")))
    arrays = {a.get("Name"): _values(a) for a in piece.find("Cells")}
    cells, start = [], 0
    for end in arrays["offsets"]:
        cells.append(arrays["connectivity"][start:end])
        start = end
    out = {"points": points, "cells": cells, "point_data": {}, "cell_data": {}}
    for tag, key in (("PointData", "point_data"), ("CellData", "cell_data")):
        node = piece.find(tag)
        if node is not None:
            for a in node:
                out[key][a.get("Name")] = _grouped(a, _values(a))
    return out


def read_pieces(path):
    """The pieces of a .pvtu (one list entry per piece file), or [the piece] of a .vtu."""
    if not path.endswith(".pvtu"):
        return [read_piece(path)]
    root = ET.parse(path).getroot()
    files = [p.get("Source") for p in root.iter("Piece")]
    return [read_piece(os.path.join(os.path.dirname(path), f)) for f in files]
