#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
# Copyright 2026 The freeform_inspection authors
"""How far off a known pose may be: freeform_inspect --initial-pose from the truth turned about
random axes through the CAD's origin and moved by a share of L, a few guesses per cell; prints
each guess's status and how far the refined pose lies from the truth [deg].

  python3 bench/initial_pose_basin.py CLI [--cad F --cad-scale S --scan F --truth F]
                                          [--angles 5,10,...] [--shifts 0,0.01,...] [--cases N]

Defaults: the README's sample (data/blade/blade_fine.stl in mm, data/blade/blade_scan.ply and
its truth). Standard library only (no numpy on a bare Debian 12).
"""
import argparse
import json
import math
import os
import random
import subprocess

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def turn(axis, deg):
    """Rodrigues' rotation matrix about `axis` by `deg`."""
    n = math.sqrt(sum(v * v for v in axis))
    x, y, z = (v / n for v in axis)
    a = math.radians(deg)
    c, s, t = math.cos(a), math.sin(a), 1.0 - math.cos(a)
    return [[c + x * x * t, x * y * t - z * s, x * z * t + y * s],
            [y * x * t + z * s, c + y * y * t, y * z * t - x * s],
            [z * x * t - y * s, z * y * t + x * s, c + z * z * t]]


def angle_deg(a, b):
    trace = sum(a[k][i] * b[k][i] for i in range(3) for k in range(3))
    return math.degrees(math.acos(max(-1.0, min(1.0, (trace - 1.0) / 2.0))))


def run(args, pose):
    numbers = " ".join("%.17g" % pose[r][c] for r in range(3) for c in range(4))
    out = subprocess.run([args.cli, "--cad", args.cad, "--cad-scale", str(args.cad_scale),
                          "--scan", args.scan, "--initial-pose", numbers],
                         capture_output=True, text=True, check=False)
    report = json.loads(out.stdout)
    return report["status"], report["transform_cad_from_scan"], report["timings_s"]["total"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("cli")
    parser.add_argument("--cad", default=os.path.join(ROOT, "data/blade/blade_fine.stl"))
    parser.add_argument("--cad-scale", type=float, default=0.001)
    parser.add_argument("--scan", default=os.path.join(ROOT, "data/blade/blade_scan.ply"))
    parser.add_argument("--truth", default=os.path.join(ROOT, "data/blade/blade_scan_T_cad_scan.txt"))
    parser.add_argument("--diagonal", type=float, default=0.1588, help="L of the CAD [m]")
    parser.add_argument("--angles", default="5,10,15,20,30,45,60,90,120,180")
    parser.add_argument("--shifts", default="0,0.01,0.02,0.05", help="shares of L")
    parser.add_argument("--cases", type=int, default=4)
    parser.add_argument("--seed", type=int, default=5)
    args = parser.parse_args()
    with open(args.truth) as f:
        truth = [[float(v) for v in line.split()] for line in f if line.strip()]
    rng = random.Random(args.seed)
    print("| turn [deg] | shift [L] | ok near the truth | ok elsewhere | failed | median s |")
    print("|---|---|---|---|---|---|")
    for deg in (float(a) for a in args.angles.split(",")):
        for shift in (float(s) for s in args.shifts.split(",")):
            near = elsewhere = failed = 0
            seconds = []
            for _ in range(args.cases):
                r = turn([rng.gauss(0, 1) for _ in range(3)], deg)
                d = [rng.gauss(0, 1) for _ in range(3)]
                n = math.sqrt(sum(v * v for v in d))
                off = [r[i] + [shift * args.diagonal * d[i] / n] for i in range(3)]
                off.append([0.0, 0.0, 0.0, 1.0])
                status, pose, total = run(args, matmul(off, truth))
                seconds.append(total)
                if status == "failed":
                    failed += 1
                elif angle_deg(pose, truth) < 2.0:
                    near += 1
                else:
                    elsewhere += 1
            seconds.sort()
            print("| %g | %g | %d | %d | %d | %.2f |" % (deg, shift, near, elsewhere, failed,
                                                         seconds[len(seconds) // 2]))


if __name__ == "__main__":
    main()
