#!/usr/bin/env bash
# Descriptor time and peak memory at 10k, 100k and 1M points, mesh and cloud input, one process
# per run. Build first: scripts/build -DFREEFORM_INSPECTION_BUILD_BENCH=ON
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../scripts/env.sh"
bench="${FREEFORM_BUILD}/descriptor_bench"
for mode in mesh cloud; do
  for points in 10000 100000 1000000; do
    "${bench}" "${mode}" "${points}"
  done
done
