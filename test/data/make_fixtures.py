#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
# Copyright 2026 The freeform_inspection authors
"""Writes the small static loader fixtures in this directory (see README.md).

Deliberately independent of the C++ writers, so the readers are tested against bytes that
our own code did not produce. Deterministic: running it again gives identical files.
Usage: python3 make_fixtures.py  (from any directory; writes next to this script)
"""
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))

# 10 mm cube [0, 10]^3: corner i has x = bit 0, y = bit 1, z = bit 2; faces wound outward.
CUBE_VERTICES = [((i & 1) * 10.0, ((i >> 1) & 1) * 10.0, ((i >> 2) & 1) * 10.0) for i in range(8)]
CUBE_TRIANGLES = [(0, 2, 1), (1, 2, 3), (4, 5, 6), (5, 7, 6), (0, 1, 4), (1, 5, 4),
                  (2, 6, 3), (3, 6, 7), (0, 4, 2), (2, 4, 6), (1, 3, 5), (3, 7, 5)]
CUBE_QUADS = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]

# Regular tetrahedron, edge 20*sqrt(2) mm, shifted so that float32 could not hold the
# coordinates (1010.000001 needs double precision).
TETRA_OFFSET = 1000.000001
TETRA_VERTICES = [(TETRA_OFFSET + 10 * a, TETRA_OFFSET + 10 * b, TETRA_OFFSET + 10 * c)
                  for a, b, c in [(1, 1, 1), (1, -1, -1), (-1, 1, -1), (-1, -1, 1)]]
TETRA_TRIANGLES = [(1, 3, 2), (0, 2, 3), (0, 3, 1), (0, 1, 2)]


def write(name, data):
    mode = 'wb' if isinstance(data, bytes) else 'w'
    with open(os.path.join(HERE, name), mode, newline='' if mode == 'w' else None) as f:
        f.write(data)


def cube_ascii_stl():
    lines = ['solid cube_10mm']
    for tri in CUBE_TRIANGLES:
        lines += ['  facet normal 0 0 0', '    outer loop']
        lines += ['      vertex %g %g %g' % CUBE_VERTICES[i] for i in tri]
        lines += ['    endloop', '  endfacet']
    lines.append('endsolid cube_10mm')
    write('cube_ascii.stl', '\n'.join(lines) + '\n')


def cube_binary_solid_header_stl():
    header = b'solid cube_10mm (binary, but the header starts with solid)'.ljust(80, b' ')
    out = bytearray(header + struct.pack('<I', len(CUBE_TRIANGLES)))
    for tri in CUBE_TRIANGLES:
        out += struct.pack('<3f', 0, 0, 0)
        for i in tri:
            out += struct.pack('<3f', *CUBE_VERTICES[i])
        out += struct.pack('<H', 0)
    write('cube_binary_solid_header.stl', bytes(out))


def tetra_double_binary_ply():
    header = ('ply\nformat binary_little_endian 1.0\ncomment regular tetrahedron, mm, double\n'
              'element vertex 4\nproperty double x\nproperty double y\nproperty double z\n'
              'element face 4\nproperty list uchar uint vertex_indices\nend_header\n')
    out = bytearray(header.encode('ascii'))
    for v in TETRA_VERTICES:
        out += struct.pack('<3d', *v)
    for tri in TETRA_TRIANGLES:
        out += struct.pack('<B3I', 3, *tri)
    write('tetra_double_binary.ply', bytes(out))


def cube_quads_big_endian_ply():
    header = ('ply\nformat binary_big_endian 1.0\ncomment 10 mm cube as quads\n'
              'element vertex 8\nproperty float32 x\nproperty float32 y\nproperty float32 z\n'
              'property uint8 red\nproperty uint8 green\nproperty uint8 blue\n'
              'element face 6\nproperty list uint8 int32 vertex_indices\nend_header\n')
    out = bytearray(header.encode('ascii'))
    for v in CUBE_VERTICES:
        out += struct.pack('>3f3B', *v, 200, 100, 50)
    for quad in CUBE_QUADS:
        out += struct.pack('>B4i', 4, *quad)
    write('cube_quads_big_endian.ply', bytes(out))


def scan_range_grid_ply():
    # Stanford-style range scan: 2x3 grid, one empty cell, one NaN point, normals.
    points = [(1, 2, 3, 0, 0, 1), (4, 5, 6, 0, 0, 2), ('nan', 'nan', 'nan', 0, 0, 1),
              (7, 8, 9, 0, 3, 4), (10, 11, 12, 1, 0, 0)]
    grid = [[0], [1], [], [2], [3], [4]]
    lines = ['ply', 'format ascii 1.0', 'obj_info num_cols 3', 'obj_info num_rows 2',
             'element vertex %d' % len(points)]
    lines += ['property float %s' % n for n in ('x', 'y', 'z', 'nx', 'ny', 'nz')]
    lines += ['element range_grid %d' % len(grid), 'property list uchar int vertex_indices',
              'end_header']
    lines += [' '.join(str(v) for v in p) for p in points]
    lines += [' '.join(str(v) for v in [len(cell)] + cell) for cell in grid]
    write('scan_range_grid.ply', '\n'.join(lines) + '\n')


def cube_quads_obj():
    lines = ['# 10 mm cube, quads, all corner syntaxes', 'o cube']
    lines += ['v %g %g %g' % v for v in CUBE_VERTICES]
    lines += ['vt 0 0', 'vt 1 0', 'vt 1 1', 'vn 0 0 1', 's off']
    forms = ['{}', '{}/1', '{}//1', '{}/2/1']
    for n, quad in enumerate(CUBE_QUADS[:4]):
        lines.append('f ' + ' '.join(forms[n].format(i + 1) for i in quad))
    for quad in CUBE_QUADS[4:]:  # relative indices
        lines.append('f ' + ' '.join(str(i - 8) for i in quad))
    write('cube_quads.obj', '\n'.join(lines) + '\n')


def cloud_ascii_pcd():
    points = [(1, 2, 3), (4, 5, 6), ('nan', 'nan', 'nan'), (7, 8, 9)]
    lines = ['# .PCD v0.7 - Point Cloud Data file format', 'VERSION 0.7', 'FIELDS x y z',
             'SIZE 4 4 4', 'TYPE F F F', 'COUNT 1 1 1', 'WIDTH 4', 'HEIGHT 1',
             'VIEWPOINT 0 0 0 1 0 0 0', 'POINTS 4', 'DATA ascii']
    lines += [' '.join(str(v) for v in p) for p in points]
    write('cloud_ascii.pcd', '\n'.join(lines) + '\n')


if __name__ == '__main__':
    cube_ascii_stl()
    cube_binary_solid_header_stl()
    tetra_double_binary_ply()
    cube_quads_big_endian_ply()
    scan_range_grid_ply()
    cube_quads_obj()
    cloud_ascii_pcd()
