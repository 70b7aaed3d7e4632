#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
# Copyright 2026 The freeform_inspection authors
"""Writes a finer tessellation of an STL: each triangle split into four at its edge midpoints,
LEVELS times (4^LEVELS as many faces, the same surface). A CAD exported at a tight chord
tolerance has that many faces; the benchmark of a finely tessellated CAD (docs/benchmarks.md,
"Session 47") uses it to see what the face count alone costs. Reads ASCII or binary STL, writes
binary, in the input's units.

Usage: subdivide_stl.py IN.stl OUT.stl LEVELS
"""

import struct
import sys


def read_stl(path):
    data = open(path, "rb").read()
    if data[:5] == b"solid" and b"facet" in data[:512]:
        corners = []
        for line in data.decode("ascii", "replace").splitlines():
            words = line.split()
            if words and words[0] == "vertex":
                corners.append(tuple(float(w) for w in words[1:4]))
        return [corners[i:i + 3] for i in range(0, len(corners) - 2, 3)]
    count = struct.unpack("<I", data[80:84])[0]
    triangles = []
    for i in range(count):
        start = 84 + 50 * i + 12  # after the facet normal
        values = struct.unpack("<9f", data[start:start + 36])
        triangles.append([values[0:3], values[3:6], values[6:9]])
    return triangles


def midpoint(p, q):
    return tuple((a + b) / 2.0 for a, b in zip(p, q))


def split(triangles):
    finer = []
    for a, b, c in triangles:
        ab, bc, ca = midpoint(a, b), midpoint(b, c), midpoint(c, a)
        finer += [[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]
    return finer


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    triangles = read_stl(sys.argv[1])
    for _ in range(int(sys.argv[3])):
        triangles = split(triangles)
    with open(sys.argv[2], "wb") as out:
        out.write(b"\0" * 80 + struct.pack("<I", len(triangles)))
        for t in triangles:  # zero normal: readers compute it from the winding
            out.write(struct.pack("<12fH", 0.0, 0.0, 0.0, *t[0], *t[1], *t[2], 0))
    print(len(triangles), "faces")


if __name__ == "__main__":
    main()
