#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Writes the OpenSCAD parts of bench/parts/ (drawn in millimetres) as STL in metres into OUT_DIR,
# the unit bench/run_registration_eval.sh and bench/run_camera_eval.sh read *.stl in:
#   bash bench/make_scad_parts.sh /tmp/scad_parts
#   bash bench/run_registration_eval.sh BUILD 3 /tmp/scad_parts
# Needs `apt-get install openscad` (the benchmarks only; the package never does).
# OpenSCAD 2021.01's export is not bit-stable (two runs wrote different elbow and pump cover
# files): to compare two builds, run both on the files of one run.
# Usage: bench/make_scad_parts.sh OUT_DIR
set -euo pipefail
out="$1"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
command -v openscad > /dev/null || { echo "make_scad_parts.sh: openscad not found (apt-get install openscad)" >&2; exit 1; }
mkdir -p "${out}"
for part in "${root}"/parts/*.scad; do
  name="$(basename "${part}" .scad)"
  openscad -o "${out}/${name}_mm.stl" "${part}" > /dev/null 2>&1 ||
    { echo "make_scad_parts.sh: openscad failed on ${part}" >&2; exit 1; }
  echo "scale(0.001) import(\"${out}/${name}_mm.stl\");" > "${out}/${name}_m.scad"
  openscad -o "${out}/${name}.stl" "${out}/${name}_m.scad" > /dev/null 2>&1 ||
    { echo "make_scad_parts.sh: openscad failed scaling ${part}" >&2; exit 1; }
  rm "${out}/${name}_mm.stl" "${out}/${name}_m.scad"
  echo "${out}/${name}.stl"
done
