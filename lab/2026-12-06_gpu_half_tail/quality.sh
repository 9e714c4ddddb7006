#!/usr/bin/env bash
# The quality cost of each tail variant on this machine's CPU renderer
# (lavapipe): cavity quality at half resolution, the upsample's include
# replaced through --kernel-source (the AO the fused tail writes is the
# include's), against the ray-traced ground truth.
#   bash lab/2026-12-06_gpu_half_tail/quality.sh   (writes quality_<variant>_<size>.txt)
set -euo pipefail
cd "$(dirname "$0")/../.."
here=lab/2026-12-06_gpu_half_tail
for size in 320x180 640x360; do
  for v in committed bilinear depth_only; do
    src=()
    [ "$v" = bilinear ] && src=(--kernel-source include/upsample.glsl=$here/upsample_bilinear.glsl)
    [ "$v" = depth_only ] && src=(--kernel-source include/upsample.glsl=$here/upsample_depth_only.glsl)
    build/harness/cavity quality --kernel alchemy_fast,hemisphere_fast --samples 16 --res $size \
      --resolution half "${src[@]}" --quiet > $here/quality_${v}_$size.txt 2>&1
  done
done
