#!/usr/bin/env bash
# hemisphere_fast with its rays' structure compiled in (steps = 4 assumed,
# the default: ray g is points 4g .. 4g + 3), two probes given by
# --kernel-source, on the H200, in one call:
# 1. cavity ab, 4 rounds, B against B with hemisphere_rays.glsl (one ray an
#    iteration on GL, unrolled on Vulkan), then with hemisphere_rays2.glsl
#    (two rays an iteration on GL).
# 2. The gpu matrix's hemisphere_fast pipelines rendered with each probe and
#    judged by digest against the approved ones.
set -uo pipefail
. scripts/gpu_env.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
D=lab/2026-12-04_h200_hemisphere_rays
K=/tmp/keep; rm -rf $K; mkdir -p $K
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $K/gpu.txt 2>&1
filter='^corner/hemisphere_fast/n(16|32)/b4/full/1920x1080/(gl|vk)/compute/'
filter+='|^corner/hemisphere_fast/n16/b4/fused_tail=1/half/1920x1080/(gl|vk)/compute/'
for v in hemisphere_rays hemisphere_rays2; do
  smi_start $K/ab_$v.clocks.csv
  .bundle/cavity.sh ab --a .bundle --b .bundle --rounds 4 --filter "$filter" \
    --bench-args='--sweep gpu --max-time 0.3' --b-args="--kernel-source ssao_hemisphere_fast.glsl=$D/$v.glsl" \
    --out $K/ab_$v > $K/ab_$v.txt 2>&1
  echo "== ab $v: rc $? ($(el) s)"; smi_stop
  grep -E "compute +ao " $K/ab_$v.txt | cut -c1-140
done
work=/tmp/refs; rm -rf $work; mkdir -p $work; cp -r baselines $work/base
for v in hemisphere_rays hemisphere_rays2; do
  .bundle/render.sh --matrix gpu --filter '/hemisphere_fast/' --baselines $work/base \
    --kernel-source ssao_hemisphere_fast.glsl=$D/$v.glsl --out $work/r_$v > $K/render_$v.txt 2>&1
  echo "== render $v: rc $? ($(el) s)"
  .bundle/cavity.sh gate judge $work/r_$v --baselines $work/base --out $work/g_$v --quiet > $K/judge_$v.md 2>&1
  echo "== judge $v: rc $?"; head -3 $K/judge_$v.md
done
tar czf $OUT/call1.tgz -C /tmp keep; echo "all: $(el) s"
