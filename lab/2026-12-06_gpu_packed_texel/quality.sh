#!/usr/bin/env bash
# The fast kernels' MAE against the ground truth, before and after the
# pyramid's 32-bit texel, on this machine's CPU renderer (lavapipe): run once
# with the build before the change and once after, then compare.
#   bash lab/2026-12-06_gpu_packed_texel/quality.sh NAME   (writes quality_<size>_NAME.txt and /tmp/q_<size>_NAME/)
#   python3 lab/2026-12-06_gpu_packed_texel/quality_delta.py before after
set -euo pipefail
cd "$(dirname "$0")/../.."
name=${1:?usage: quality.sh NAME}
for size in 320x180 640x360; do
  build/harness/cavity quality --kernel alchemy_fast,hemisphere_fast,ssdo_fast --samples 16,32 --res $size \
    --out /tmp/q_${size}_$name > lab/2026-12-06_gpu_packed_texel/quality_${size}_$name.txt 2>&1
done
