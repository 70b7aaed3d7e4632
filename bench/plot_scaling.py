#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
# Copyright 2026 The freeform_inspection authors
"""Plots the scaling run of bench/pcl_compare (--scaling --json FILE): median seconds per scan
against scan size, log-log, our stages and PCL's. Uses matplotlib when it is installed (Debian:
python3-matplotlib); otherwise draws the same plot itself and writes the PNG with zlib, so the
benchmark needs nothing beyond python3.

Usage: plot_scaling.py SCALING_JSON OUT_PNG
"""

import json
import math
import struct
import sys
import zlib

# (label, method, stages summed; None = the method's registration time), colour, dashed
SERIES = [
    ("ours: registration", "ours", None, (0, 90, 181), False),
    ("ours: descriptors", "ours", ["descriptors"], (86, 180, 233), False),
    ("ours: features + global", "ours",
     ["features", "correspondences", "global_registration"], (0, 158, 115), False),
    ("ours: ICP + verification", "ours", ["icp", "verification"], (120, 120, 120), False),
    ("PCL: total", "pcl", None, (213, 94, 0), True),
    ("PCL: normals + FPFH", "pcl", ["voxel_grid", "normals", "fpfh"], (230, 159, 0), True),
    ("PCL: SAC", "pcl", ["sac"], (204, 121, 167), True),
    ("PCL: ICP", "pcl", ["icp"], (90, 40, 40), True),
]
TITLE = "Registration time per scan vs scan size (blade, full view, 0.5% noise)"
X_LABEL = "scan points"
Y_LABEL = "seconds (median)"


def load_series(path):
    """[(label, colour, dashed, [(points, seconds), ...]), ...] from the scaling JSON."""
    with open(path, encoding="utf-8") as f:
        rows = json.load(f)["scaling"]
    out = []
    for label, method, stages, colour, dashed in SERIES:
        points = []
        for row in rows:
            if row["method"] != method:
                continue
            if stages is None:
                seconds = row["median_s"]
            else:
                seconds = sum(row["median_stage_s"].get(s) or 0.0 for s in stages)
            if seconds and seconds > 0:
                points.append((row["points"], seconds))
        if points:
            out.append((label, colour, dashed, sorted(points)))
    return out


def plot_matplotlib(series, png):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(9, 5.6), dpi=100)
    for label, colour, dashed, points in series:
        ax.plot([p for p, _ in points], [s for _, s in points], "--" if dashed else "-",
                marker="o", color=[c / 255 for c in colour], label=label)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(X_LABEL)
    ax.set_ylabel(Y_LABEL)
    ax.set_title(TITLE)
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(loc="upper left", fontsize=8)
    fig.tight_layout()
    fig.savefig(png)


# ---- fallback: a small rasteriser with a 5x7 bitmap font, PNG written with zlib ----

# Seven rows of five pixels per character, top row first.
GLYPHS = {
    'A': ".###. #...# #...# ##### #...# #...# #...#",
    'B': "####. #...# #...# ####. #...# #...# ####.",
    'C': ".###. #...# #.... #.... #.... #...# .###.",
    'D': "####. #...# #...# #...# #...# #...# ####.",
    'E': "##### #.... #.... ####. #.... #.... #####",
    'F': "##### #.... #.... ####. #.... #.... #....",
    'G': ".###. #...# #.... #.### #...# #...# .###.",
    'H': "#...# #...# #...# ##### #...# #...# #...#",
    'I': ".###. ..#.. ..#.. ..#.. ..#.. ..#.. .###.",
    'J': "..### ...#. ...#. ...#. ...#. #..#. .##..",
    'K': "#...# #..#. #.#.. ##... #.#.. #..#. #...#",
    'L': "#.... #.... #.... #.... #.... #.... #####",
    'M': "#...# ##.## #.#.# #.#.# #...# #...# #...#",
    'N': "#...# #...# ##..# #.#.# #..## #...# #...#",
    'O': ".###. #...# #...# #...# #...# #...# .###.",
    'P': "####. #...# #...# ####. #.... #.... #....",
    'Q': ".###. #...# #...# #...# #.#.# #..#. .##.#",
    'R': "####. #...# #...# ####. #.#.. #..#. #...#",
    'S': ".#### #.... #.... .###. ....# ....# ####.",
    'T': "##### ..#.. ..#.. ..#.. ..#.. ..#.. ..#..",
    'U': "#...# #...# #...# #...# #...# #...# .###.",
    'V': "#...# #...# #...# #...# #...# .#.#. ..#..",
    'W': "#...# #...# #...# #.#.# #.#.# #.#.# .#.#.",
    'X': "#...# #...# .#.#. ..#.. .#.#. #...# #...#",
    'Y': "#...# #...# .#.#. ..#.. ..#.. ..#.. ..#..",
    'Z': "##### ....# ...#. ..#.. .#... #.... #####",
    'a': "..... ..... .###. ....# .#### #...# .####",
    'b': "#.... #.... ####. #...# #...# #...# ####.",
    'c': "..... ..... .###. #.... #.... #...# .###.",
    'd': "....# ....# .#### #...# #...# #...# .####",
    'e': "..... ..... .###. #...# ##### #.... .###.",
    'f': "..##. .#..# .#... ###.. .#... .#... .#...",
    'g': "..... .#### #...# #...# .#### ....# .###.",
    'h': "#.... #.... #.##. ##..# #...# #...# #...#",
    'i': "..#.. ..... .##.. ..#.. ..#.. ..#.. .###.",
    'j': "...#. ..... ..##. ...#. ...#. #..#. .##..",
    'k': "#.... #.... #..#. #.#.. ##... #.#.. #..#.",
    'l': ".##.. ..#.. ..#.. ..#.. ..#.. ..#.. .###.",
    'm': "..... ..... ##.#. #.#.# #.#.# #...# #...#",
    'n': "..... ..... #.##. ##..# #...# #...# #...#",
    'o': "..... ..... .###. #...# #...# #...# .###.",
    'p': "..... ..... ####. #...# ####. #.... #....",
    'q': "..... ..... .#### #...# .#### ....# ....#",
    'r': "..... ..... #.##. ##..# #.... #.... #....",
    's': "..... ..... .#### #.... .###. ....# ####.",
    't': ".#... .#... ###.. .#... .#... .#..# ..##.",
    'u': "..... ..... #...# #...# #...# #..## .##.#",
    'v': "..... ..... #...# #...# #...# .#.#. ..#..",
    'w': "..... ..... #...# #...# #.#.# #.#.# .#.#.",
    'x': "..... ..... #...# .#.#. ..#.. .#.#. #...#",
    'y': "..... ..... #...# #...# .#### ....# .###.",
    'z': "..... ..... ##### ...#. ..#.. .#... #####",
    '0': ".###. #...# #..## #.#.# ##..# #...# .###.",
    '1': "..#.. .##.. ..#.. ..#.. ..#.. ..#.. .###.",
    '2': ".###. #...# ....# ...#. ..#.. .#... #####",
    '3': "##### ...#. ..#.. ...#. ....# #...# .###.",
    '4': "...#. ..##. .#.#. #..#. ##### ...#. ...#.",
    '5': "##### #.... ####. ....# ....# #...# .###.",
    '6': "..##. .#... #.... ####. #...# #...# .###.",
    '7': "##### ....# ...#. ..#.. .#... .#... .#...",
    '8': ".###. #...# #...# .###. #...# #...# .###.",
    '9': ".###. #...# #...# .#### ....# ...#. .##..",
    ' ': "..... ..... ..... ..... ..... ..... .....",
    '.': "..... ..... ..... ..... ..... .##.. .##..",
    ',': "..... ..... ..... ..... .##.. ..#.. .#...",
    ':': "..... .##.. .##.. ..... .##.. .##.. .....",
    '%': "##... ##..# ...#. ..#.. .#... #..## ...##",
    '+': "..... ..#.. ..#.. ##### ..#.. ..#.. .....",
    '-': "..... ..... ..... ##### ..... ..... .....",
    '(': "...#. ..#.. .#... .#... .#... ..#.. ...#.",
    ')': ".#... ..#.. ...#. ...#. ...#. ..#.. .#...",
    '/': "..... ....# ...#. ..#.. .#... #.... .....",
    '=': "..... ..... ##### ..... ##### ..... .....",
    '[': ".###. .#... .#... .#... .#... .#... .###.",
    ']': ".###. ...#. ...#. ...#. ...#. ...#. .###.",
    '_': "..... ..... ..... ..... ..... ..... #####",
}


class Canvas:
    def __init__(self, width, height):
        self.width, self.height = width, height
        self.pixels = bytearray(b"\xff" * (width * height * 3))

    def dot(self, x, y, colour):
        x, y = int(round(x)), int(round(y))
        if 0 <= x < self.width and 0 <= y < self.height:
            i = (y * self.width + x) * 3
            self.pixels[i:i + 3] = bytes(colour)

    def disc(self, x, y, radius, colour):
        r = int(math.ceil(radius))
        for dy in range(-r, r + 1):
            for dx in range(-r, r + 1):
                if dx * dx + dy * dy <= radius * radius:
                    self.dot(x + dx, y + dy, colour)

    def line(self, x0, y0, x1, y1, colour, width=1.0, dash=None):
        length = math.hypot(x1 - x0, y1 - y0)
        steps = max(1, int(length * 2))
        for k in range(steps + 1):
            t = k / steps
            if dash and (t * length) % (dash[0] + dash[1]) > dash[0]:
                continue
            x, y = x0 + t * (x1 - x0), y0 + t * (y1 - y0)
            if width <= 1.0:
                self.dot(x, y, colour)
            else:
                self.disc(x, y, width / 2, colour)

    def text(self, x, y, text, colour=(0, 0, 0), scale=2, anchor="left", vertical=False):
        """Draws `text` with its top-left at (x, y) ('center'/'right' shift it left)."""
        advance = 6 * scale
        shift = {"left": 0, "center": len(text) * advance / 2, "right": len(text) * advance}
        start = -shift[anchor]
        for n, char in enumerate(text):
            glyph = GLYPHS.get(char, "##### " * 7).replace(" ", "")
            for row in range(7):
                for col in range(5):
                    if glyph[row * 5 + col] != "#":
                        continue
                    for sy in range(scale):
                        for sx in range(scale):
                            u = start + n * advance + col * scale + sx
                            v = row * scale + sy
                            if vertical:
                                self.dot(x + v, y - u, colour)
                            else:
                                self.dot(x + u, y + v, colour)

    def png(self, path):
        raw = b"".join(b"\x00" + bytes(self.pixels[y * self.width * 3:(y + 1) * self.width * 3])
                       for y in range(self.height))

        def chunk(kind, data):
            body = kind + data
            return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))

        header = struct.pack(">IIBBBBB", self.width, self.height, 8, 2, 0, 0, 0)
        with open(path, "wb") as f:
            f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) +
                    chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def tick_label(value, axis):
    if axis == "x":
        return {1e3: "1k", 1e4: "10k", 1e5: "100k", 1e6: "1M", 1e7: "10M"}.get(value, "%g" % value)
    return "%g" % value


def plot_fallback(series, png):
    width, height = 1100, 620
    left, right, top, bottom = 110, 350, 60, 80
    canvas = Canvas(width, height)
    xs = [p for *_, points in series for p, _ in points]
    ys = [s for *_, points in series for _, s in points]
    x_lo, x_hi = math.floor(math.log10(min(xs))), math.ceil(math.log10(max(xs)))
    y_lo, y_hi = math.floor(math.log10(min(ys))), math.ceil(math.log10(max(ys)))

    def px(x):
        return left + (math.log10(x) - x_lo) / (x_hi - x_lo) * (width - left - right)

    def py(y):
        return height - bottom - (math.log10(y) - y_lo) / (y_hi - y_lo) * (height - top - bottom)

    grey, black = (225, 225, 225), (0, 0, 0)
    for e in range(x_lo, x_hi + 1):
        x = px(10.0 ** e)
        canvas.line(x, top, x, height - bottom, grey)
        canvas.text(x, height - bottom + 12, tick_label(10.0 ** e, "x"), anchor="center")
    for e in range(y_lo, y_hi + 1):
        y = py(10.0 ** e)
        canvas.line(left, y, width - right, y, grey)
        canvas.text(left - 8, y - 7, tick_label(10.0 ** e, "y"), anchor="right")
    for x0, y0, x1, y1 in [(left, top, width - right, top), (left, height - bottom, width - right,
                                                             height - bottom),
                           (left, top, left, height - bottom),
                           (width - right, top, width - right, height - bottom)]:
        canvas.line(x0, y0, x1, y1, black)
    canvas.text(width / 2, 20, TITLE, anchor="center")
    canvas.text((left + width - right) / 2, height - 40, X_LABEL, anchor="center")
    canvas.text(30, (top + height - bottom) / 2, Y_LABEL, anchor="center", vertical=True)
    for n, (label, colour, dashed, points) in enumerate(series):
        dash = (9, 6) if dashed else None
        for (xa, ya), (xb, yb) in zip(points, points[1:]):
            canvas.line(px(xa), py(ya), px(xb), py(yb), colour, width=2.5, dash=dash)
        for x, y in points:
            canvas.disc(px(x), py(y), 4, colour)
        ly = top + 10 + n * 26
        canvas.line(width - right + 15, ly + 7, width - right + 50, ly + 7, colour, 2.5, dash)
        canvas.text(width - right + 58, ly, label)
    canvas.png(png)


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: plot_scaling.py SCALING_JSON OUT_PNG")
    series = load_series(sys.argv[1])
    if not series:
        sys.exit("plot_scaling.py: no scaling rows in " + sys.argv[1])
    try:
        plot_matplotlib(series, sys.argv[2])
        how = "matplotlib"
    except ImportError:
        plot_fallback(series, sys.argv[2])
        how = "built-in renderer (matplotlib not installed)"
    print("wrote %s (%s)" % (sys.argv[2], how))


if __name__ == "__main__":
    main()
