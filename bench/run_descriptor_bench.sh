#!/usr/bin/env bash
# Descriptor time and peak memory at 10k, 30k, 100k and 1M points, mesh and cloud input, and
# one unorganized camera view at 30k and 100k points; one process per run, each size RUNS times
# (default 3): the machine is shared, so report the minimum time of the runs.
# Build first: scripts/build -DFREEFORM_INSPECTION_BUILD_BENCH=ON
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../scripts/env.sh"
bench="${FREEFORM_BUILD}/descriptor_bench"
runs="${RUNS:-3}"
for mode in mesh cloud; do
  for points in 10000 30000 100000 1000000; do
    for ((run = 0; run < runs; ++run)); do
      "${bench}" "${mode}" "${points}"
    done
  done
done
for points in 30000 100000; do
  for ((run = 0; run < runs; ++run)); do
    "${bench}" view "${points}"
  done
done
