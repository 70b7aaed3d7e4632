#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Our registration against PCL's standard pipeline (bench/pcl_compare): the case-set table over
# every part, the real range scans of the Stanford dragon when given, then the scaling run on
# the blade and its plot (docs/scaling.png).
# Usage: bench/run_pcl_compare.sh BUILD_DIR [CASES] [MESH_DIR] [OUT_DIR] [DRAGON_DIR]
#   BUILD_DIR  a build configured with -DFREEFORM_INSPECTION_BUILD_BENCH=ON (target pcl_compare)
#   CASES      cases per part and set (default 2; 2 keeps a run with the 7 shared meshes
#              under 30 minutes on 2 cores)
#   MESH_DIR   extra CAD meshes besides the shipped blade: *.stl in metres (robot links),
#              *.obj in millimetres (ABC models)
#   OUT_DIR    where the tables, JSON and logs go (default BUILD_DIR/pcl_compare)
#   DRAGON_DIR the dragon_stand scans (dragonStandRight.conf and its PLYs): each view registered
#              to the next, ours with registration.min_surface_on_cad 0.5 (two views share
#              55-94 % of their surface)
# Prints both markdown tables; the JSON files are for scripts, the logs have one line per case.
set -euo pipefail
build="$1"
cases="${2:-2}"
mesh_dir="${3:-}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${4:-${build}/pcl_compare}"
dragon_dir="${5:-}"
bin="${build}/pcl_compare"
mkdir -p "${out}"

parts=(--cad "${root}/data/blade/blade.stl" --cad-scale 0.001)
if [ -n "${mesh_dir}" ]; then
  for mesh in "${mesh_dir}"/*.stl; do
    if [ -e "${mesh}" ]; then
      parts+=(--cad "${mesh}" --cad-scale 1)
    fi
  done
  for mesh in "${mesh_dir}"/*.obj; do
    if [ -e "${mesh}" ]; then
      parts+=(--cad "${mesh}" --cad-scale 0.001)
    fi
  done
fi

echo "## Case sets (${cases} cases per part and set)"
echo
"${bin}" "${parts[@]}" --cases "${cases}" --json "${out}/pcl_compare.json" \
  2>"${out}/pcl_compare.log" | tee "${out}/pcl_compare.md"
if [ -n "${dragon_dir}" ]; then
  echo
  echo "## The Stanford dragon's range scans (each view to the next)"
  echo
  "${bin}" --dragon "${dragon_dir}" --min-surface 0.5 --json "${out}/pcl_dragon.json" \
    2>"${out}/pcl_dragon.log" | tee "${out}/pcl_dragon.md"
fi
echo
echo "## Scaling (blade, full view, 0.5% noise, 1 case per size)"
echo
"${bin}" --cad "${root}/data/blade/blade.stl" --cad-scale 0.001 --scaling --cases 1 \
  --json "${out}/pcl_scaling.json" 2>"${out}/pcl_scaling.log" | tee "${out}/pcl_scaling.md"
python3 "${root}/bench/plot_scaling.py" "${out}/pcl_scaling.json" "${root}/docs/scaling.png"
