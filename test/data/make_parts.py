#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
# Copyright 2026 The freeform_inspection authors
"""Writes generated test parts (see README.md): shapes of the kinds the package inspects that
the public meshes lack. Python 3 standard library only, deterministic, metres.
Usage: python3 make_parts.py          writes meshes/bent_sheet_bracket.stl,
                                      meshes/hat_channel.stl and meshes/box_bar.stl (the
                                      tests use them)
       python3 make_parts.py DIR      writes those two, a lumpy casting and an open freeform
                                      panel into DIR, for bench/registration_eval
                                      (docs/benchmarks.md)
"""
import math
import os
import struct
import sys

HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'meshes')


def write_binary_stl(path, triangles):
    out = bytearray(b'freeform_inspection test part'.ljust(80, b' '))
    out += struct.pack('<I', len(triangles))
    for a, b, c in triangles:
        u = [b[i] - a[i] for i in range(3)]
        v = [c[i] - a[i] for i in range(3)]
        n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
        length = math.sqrt(sum(x * x for x in n)) or 1.0
        out += struct.pack('<12fH', *(x / length for x in n), *a, *b, *c, 0)
    with open(path, 'wb') as f:
        f.write(bytes(out))


def quads(rows, flip=False):
    """Two triangles per grid quad of rows[i][j]; flip reverses the winding."""
    triangles = []
    for i in range(len(rows) - 1):
        for j in range(len(rows[i]) - 1):
            a, b, c, d = rows[i][j], rows[i + 1][j], rows[i + 1][j + 1], rows[i][j + 1]
            triangles += [(a, c, b), (a, d, c)] if flip else [(a, b, c), (a, c, d)]
    return triangles


def sheet(line, thickness, length, across, lift):
    """A sheet of `thickness` whose mid-surface is the profile `line` (x, z points) swept along
    y over `length` (`across` rows), each face pushed out by lift(i, y) at profile point i (an
    embossing moves both faces). Closed by its side walls and end caps, wound outward."""
    normals = []
    for i in range(len(line)):
        (x0, z0), (x1, z1) = line[max(i - 1, 0)], line[min(i + 1, len(line) - 1)]
        size = math.hypot(x1 - x0, z1 - z0)
        normals.append((-(z1 - z0) / size, (x1 - x0) / size))
    outer, inner = [], []
    for i, (x, z) in enumerate(line):
        nx, nz = normals[i]
        row_out, row_in = [], []
        for j in range(across):
            y = length * j / (across - 1)
            up = lift(i, y)
            row_out.append((x + nx * (thickness / 2 + up), y, z + nz * (thickness / 2 + up)))
            row_in.append((x - nx * (thickness / 2 - up), y, z - nz * (thickness / 2 - up)))
        outer.append(row_out)
        inner.append(row_in)
    triangles = quads(outer) + quads(inner, flip=True)
    last = across - 1
    triangles += quads([[outer[i][0], inner[i][0]] for i in range(len(line))], flip=True)
    triangles += quads([[outer[i][last], inner[i][last]] for i in range(len(line))])
    triangles += quads([outer[0], inner[0]], flip=True)
    triangles += quads([outer[-1], inner[-1]])
    return triangles


def bent_sheet_bracket():
    """A stamped bracket: a 2 mm sheet, 120 mm wide, legs of 100 mm and 70 mm joined by a 90°
    bend of 10 mm radius, with a 3 mm bead embossed off-centre on the long leg. Closed, wound
    outward. Its legs of unequal length make a view of the bend alone symmetric about the
    bend's bisector, which the part is not; its width makes a view of one leg slide along it."""
    line = [(0.1 * k / 20, 0.0) for k in range(21)]  # long leg along x
    bend = 0.01
    for k in range(1, 9):
        a = -math.pi / 2 + (math.pi / 2) * k / 8
        line.append((0.1 + bend * math.cos(a), bend + bend * math.sin(a)))
    line += [(0.11, bend + 0.06 * k / 12) for k in range(1, 13)]  # short leg along z

    def bead(i, y):
        if i > 20:
            return 0.0
        return 0.003 * math.exp(-(line[i][0] - 0.045) ** 2 / 1e-4 - (y - 0.08) ** 2 / 2e-4)

    return sheet(line, 0.002, 0.12, 25, bead)


def hat_channel():
    """A stamped hat channel: a 1.5 mm sheet folded into a 40 × 30 mm U with flanges of 30 and
    15 mm, 150 mm long, a 2 mm dimple on the wide flange. Closed, wound outward. Turned by 180°
    about its vertical axis it lies on itself but for the flanges' difference."""
    corners = [(-0.05, 0.0), (-0.02, 0.0), (-0.02, 0.03), (0.02, 0.03), (0.02, 0.0), (0.035, 0.0)]
    line = []
    for (x0, z0), (x1, z1) in zip(corners[:-1], corners[1:]):
        steps = max(2, int(math.hypot(x1 - x0, z1 - z0) / 0.003))
        line += [(x0 + (x1 - x0) * k / steps, z0 + (z1 - z0) * k / steps) for k in range(steps)]
    line.append(corners[-1])

    def dimple(i, y):
        x, z = line[i]
        if abs(z) > 1e-9 or x > -0.02:
            return 0.0
        return 0.002 * math.exp(-(x + 0.035) ** 2 / 5e-5 - (y - 0.04) ** 2 / 5e-5)

    return sheet(line, 0.0015, 0.15, 31, dimple)


def lumpy_casting():
    """A closed egg-shaped body about 150 mm long with five smooth lumps and a dent, none of
    them placed symmetrically: a casting without flat faces or edges."""
    around, up, radius = 96, 49, 0.07
    lumps = [((0.3, 0.2, 0.93), 0.18, 0.25), ((-0.7, 0.5, 0.5), 0.12, 0.35),
             ((0.1, -0.9, -0.4), -0.10, 0.3), ((0.6, -0.3, -0.7), 0.22, 0.2),
             ((-0.4, -0.2, 0.9), 0.08, 0.15)]

    def r(x, y, z):
        value = 1.0 + 0.25 * x * x - 0.15 * z
        for (cx, cy, cz), height, spread in lumps:
            length = math.sqrt(cx * cx + cy * cy + cz * cz)
            d2 = (x - cx / length) ** 2 + (y - cy / length) ** 2 + (z - cz / length) ** 2
            value += height * math.exp(-d2 / (spread * spread))
        return radius * value

    rows = []
    for i in range(around):
        theta = 2 * math.pi * i / around
        row = []
        for j in range(up):
            phi = math.pi * j / (up - 1)
            x, y, z = math.sin(phi) * math.cos(theta), math.sin(phi) * math.sin(theta), math.cos(phi)
            length = r(x, y, z)
            row.append((length * x, 0.8 * length * y, length * z))
        rows.append(row)
    triangles = []
    for i in range(around):
        k = (i + 1) % around
        for j in range(up - 1):
            a, b, c, d = rows[i][j], rows[k][j], rows[k][j + 1], rows[i][j + 1]
            if j == 0:
                triangles.append((a, d, c))  # at the pole a and b coincide
            elif j == up - 2:
                triangles.append((a, d, b))  # at the pole c and d coincide
            else:
                triangles += [(a, d, c), (a, c, b)]
    return triangles


def freeform_panel():
    """An open single surface 300 × 200 mm (a car-body panel's surface model): a wave, a rise
    towards one edge, a bump and a dent."""
    rows = []
    for i in range(121):
        x = 0.3 * i / 120
        row = []
        for j in range(81):
            y = 0.2 * j / 80
            z = (0.03 * math.sin(math.pi * x / 0.3) * math.cos(0.5 * math.pi * y / 0.2)
                 + 0.012 * math.exp(-((x - 0.2) ** 2 + (y - 0.07) ** 2) / 0.0008)
                 - 0.006 * math.exp(-((x - 0.08) ** 2 + (y - 0.15) ** 2) / 0.0004)
                 + 0.02 * (y / 0.2) ** 2)
            row.append((x, y, z))
        rows.append(row)
    return quads(rows)


def box_bar():
    """A 10 x 20 x 100 mm bar centred on the origin: 8 corners, each face two triangles."""
    half = (0.005, 0.01, 0.05)

    def corner(sx, sy, sz):
        return (sx * half[0], sy * half[1], sz * half[2])

    faces = []
    for axis in range(3):
        for sign in (-1, 1):
            # The face's four corners counter-clockwise seen from outside.
            u, v = (axis + 1) % 3, (axis + 2) % 3
            ring = []
            for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                s = [0, 0, 0]
                s[axis], s[u], s[v] = sign, su * sign, sv
                ring.append(corner(*s))
            faces.append((ring[0], ring[1], ring[2]))
            faces.append((ring[0], ring[2], ring[3]))
    return faces


if __name__ == '__main__':
    write_binary_stl(os.path.join(HERE, 'bent_sheet_bracket.stl'), bent_sheet_bracket())
    write_binary_stl(os.path.join(HERE, 'hat_channel.stl'), hat_channel())
    write_binary_stl(os.path.join(HERE, 'box_bar.stl'), box_bar())
    if len(sys.argv) > 1:
        os.makedirs(sys.argv[1], exist_ok=True)
        write_binary_stl(os.path.join(sys.argv[1], 'bent_sheet_bracket.stl'), bent_sheet_bracket())
        write_binary_stl(os.path.join(sys.argv[1], 'hat_channel.stl'), hat_channel())
        write_binary_stl(os.path.join(sys.argv[1], 'lumpy_casting.stl'), lumpy_casting())
        write_binary_stl(os.path.join(sys.argv[1], 'freeform_panel.stl'), freeform_panel())
