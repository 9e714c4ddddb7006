#!/usr/bin/env bash
# One device call: the half-resolution frame's tail (the fused upsample and
# composite) against two variants that read less, each with cavity ab on
# one build (A as committed, B with the variant through --kernel-source),
# 4 rounds, both APIs; the full pipelines ride along as the control (no
# tail: they must not move).
#   bash lab/2026-12-06_gpu_half_tail/call1.sh   (.gl and .bundle carried)
set -uo pipefail
cd "$(dirname "$0")/../.."
. scripts/gpu_env.sh
here=lab/2026-12-06_gpu_half_tail
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
K=/tmp/keep; rm -rf $K; mkdir -p $K
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv > $K/gpu.csv 2>&1
cat $K/gpu.csv
f='^corner/(alchemy_fast|hemisphere_fast)/n16/b4/(full|fused_tail=1/half)/1920x1080/(gl|vk)/compute/'
variant() {   # NAME KERNEL_FILE VARIANT_FILE
  smi_start $K/$1.clocks.csv
  .bundle/cavity.sh ab --a .bundle --b .bundle --rounds 4 --filter "$f" --bench-args='--sweep gpu --max-time 0.3' \
    --b-args "--kernel-source $2=$here/$3" --out $K/$1 > $K/$1.txt 2>&1
  echo "$1: rc $? ($(el) s)"; smi_stop
  grep -E "compute +(downsample|upsample_composite|pipeline) " $K/$1.txt | cut -c1-170
}
variant bilinear passes/upsample_composite/upsample_composite.glsl tail_bilinear.glsl
variant depth_only include/upsample.glsl upsample_depth_only.glsl
for v in bilinear depth_only; do gzip -f $K/$v/a.json $K/$v/b.json; rm -rf $K/$v/runs; done
tar -C /tmp -czf $OUT/call1.tgz keep; ls -la $OUT; echo "all: $(el) s"
