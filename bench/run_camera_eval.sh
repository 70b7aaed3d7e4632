#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Single camera views (the virtual structured-light camera, organized grid kept) of every part,
# at two range noises: the "camera views" table of docs/benchmarks.md.
# Usage: bench/run_camera_eval.sh BUILD_DIR [CASES] [MESH_DIR]
#   BUILD_DIR  the directory holding registration_eval (-DFREEFORM_INSPECTION_BUILD_BENCH=ON)
#   CASES      views per part and noise (default 10, seeds 1..CASES)
#   MESH_DIR   extra CAD meshes besides the shipped blade: *.stl in metres, *.obj in millimetres
# Environment: EVAL_FLAGS (default empty) is added to every registration_eval call, e.g.
# EVAL_FLAGS="--table" for views in which the part rests on a table the camera sees around it.
# Prints a markdown table: successes out of CASES per part and noise, wrong poses reported `ok`,
# then the totals.
set -euo pipefail
build="$1"
cases="${2:-10}"
mesh_dir="${3:-}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
eval_bin="${build}/registration_eval"
read -r -a extra_flags <<< "${EVAL_FLAGS:-}"

parts=("${root}/data/blade/blade.stl:0.001")
if [ -n "${mesh_dir}" ]; then
  for mesh in "${mesh_dir}"/*.stl; do
    if [ -e "${mesh}" ]; then parts+=("${mesh}:1"); fi
  done
  for mesh in "${mesh_dir}"/*.obj; do
    if [ -e "${mesh}" ]; then parts+=("${mesh}:0.001"); fi
  done
fi
noises=(0.001 0.005)

declare -A total wrong
echo "| part | range noise 0.1 % L | 0.5 % L |"
echo "|---|---|---|"
for part in "${parts[@]}"; do
  file="${part%:*}"
  scale="${part##*:}"
  row="| $(basename "${file}")"
  for noise in "${noises[@]}"; do
    summary=$(FI_KEEP_GRID=1 "${eval_bin}" --cad "${file}" --cad-scale "${scale}" --camera \
                --noise "${noise}" --cases "${cases}" "${extra_flags[@]}" | tail -n 1)
    # "# success S/N, ok O, ambiguous A, failed F, wrong-but-ok W, mean T s per scan"
    read -r success ambiguous failed bad seconds < <(echo "${summary}" |
      sed -E 's/# success ([0-9]+)\/[0-9]+, ok [0-9]+, ambiguous ([0-9]+), failed ([0-9]+), wrong-but-ok ([0-9]+), mean ([0-9.]+) s per scan/\1 \2 \3 \4 \5/')
    row+=" | ${success}/${cases} (${ambiguous} ambiguous, ${failed} failed, ${bad} wrong ok; ${seconds} s)"
    total[${noise}]=$(( ${total[${noise}]:-0} + success ))
    wrong[${noise}]=$(( ${wrong[${noise}]:-0} + bad ))
  done
  echo "${row} |"
done
count=$(( ${#parts[@]} * cases ))
echo
for noise in "${noises[@]}"; do
  echo "range noise ${noise} L: ${total[${noise}]}/${count} registered, ${wrong[${noise}]} wrong poses reported ok"
done
