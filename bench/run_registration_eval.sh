#!/usr/bin/env bash
# Registration success table over parts, noise levels, views and outliers (bench/registration_eval).
# Usage: bench/run_registration_eval.sh BUILD_DIR [CASES] [MESH_DIR]
#   BUILD_DIR  a build configured with -DFREEFORM_INSPECTION_BUILD_BENCH=ON
#   CASES      cases per cell of the table (default 10)
#   MESH_DIR   extra CAD meshes to evaluate besides the shipped blade: *.stl in metres, *.obj in
#              millimetres (ABC models), as bench/run_camera_eval.sh reads them
# Environment: FIRST_SEED (default 1) is the seed of each row's first case, so other blocks of
# seeds can be run (FIRST_SEED=7 with 6 cases: seeds 7-12). EVAL_FLAGS (default empty) is added to
# every registration_eval call, e.g. EVAL_FLAGS="--config other.yaml" to compare a setting.
# Prints a markdown table: success / ok / ambiguous / failed / wrong-but-ok and the mean time.
set -euo pipefail
build="$1"
cases="${2:-10}"
first_seed="${FIRST_SEED:-1}"
read -r -a extra_flags <<< "${EVAL_FLAGS:-}"
mesh_dir="${3:-}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
eval_bin="${build}/registration_eval"

parts=("${root}/data/blade/blade.stl:0.001")
if [ -n "${mesh_dir}" ]; then
  for mesh in "${mesh_dir}"/*.stl; do
    if [ -e "${mesh}" ]; then parts+=("${mesh}:1"); fi
  done
  for mesh in "${mesh_dir}"/*.obj; do
    if [ -e "${mesh}" ]; then parts+=("${mesh}:0.001"); fi
  done
fi
sets=("full 0.5%|--noise 0.005" "full 1%|--noise 0.01" "full 2%|--noise 0.02"
      "partial 0.5%|--noise 0.005 --partial" "partial 1%|--noise 0.01 --partial"
      "partial 2%|--noise 0.02 --partial" "full 0.5% + 20% outliers|--noise 0.005 --outliers 0.2")

echo "| part | case set | success | ok | ambiguous | failed | wrong but ok | s/scan |"
echo "|---|---|---|---|---|---|---|---|"
for part in "${parts[@]}"; do
  file="${part%:*}"
  scale="${part##*:}"
  for set in "${sets[@]}"; do
    label="${set%%|*}"
    flags="${set#*|}"
    # shellcheck disable=SC2086
    summary=$("${eval_bin}" --cad "${file}" --cad-scale "${scale}" --cases "${cases}" \
                --first-seed "${first_seed}" ${flags} "${extra_flags[@]}" | tail -n 1)
    # "# success S/N, ok O, ambiguous A, failed F, wrong-but-ok W, mean T s per scan"
    read -r success ok ambiguous failed wrong seconds < <(echo "${summary}" |
      sed -E 's/# success ([0-9]+\/[0-9]+), ok ([0-9]+), ambiguous ([0-9]+), failed ([0-9]+), wrong-but-ok ([0-9]+), mean ([0-9.]+) s per scan/\1 \2 \3 \4 \5 \6/')
    echo "| $(basename "${file}") | ${label} | ${success} | ${ok} | ${ambiguous} | ${failed} | ${wrong} | ${seconds} |"
  done
done
