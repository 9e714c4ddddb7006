#!/usr/bin/env bash
# The separable blur's workgroups at 64x4 (x) and 4x64 (y), where they were
# 32x8 and 8x32, on the H200, in one call:
# 1. cavity ab, 4 rounds, A = the build before (.bundle2), B = this one.
# 2. The gpu matrix's alchemy_fast and ssdo_fast pipelines rendered with B
#    and judged by digest against the approved ones.
set -uo pipefail
. scripts/gpu_env.sh
.bundle2/unpack.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
K=/tmp/keep; rm -rf $K; mkdir -p $K
filter='^corner/(alchemy_fast|ssdo_fast)/n16/b4/full/1920x1080/(gl|vk)/compute/'
filter+='|^corner/alchemy_fast/n16/b4/((fused_tail=1/)?half)/1920x1080/(gl|vk)/compute/'
smi_start $K/ab.clocks.csv
.bundle/cavity.sh ab --a .bundle2 --b .bundle --rounds 4 --filter "$filter" \
  --bench-args='--sweep gpu --max-time 0.3' --out $K/ab > $K/ab.txt 2>&1
echo "== ab: rc $? ($(el) s)"; smi_stop
grep -E "compute +(blur_x|blur_y|indirect_blur_x|indirect_blur_y|pipeline) " $K/ab.txt | cut -c1-130
work=/tmp/refs; rm -rf $work; mkdir -p $work; cp -r baselines $work/base
.bundle/render.sh --matrix gpu --filter '/(alchemy_fast|ssdo_fast)/' --baselines $work/base --out $work/r > $K/render.txt 2>&1
echo "== render: rc $? ($(el) s)"
.bundle/cavity.sh gate judge $work/r --baselines $work/base --out $work/g --quiet > $K/judge.md 2>&1
echo "== judge: rc $?"; head -3 $K/judge.md
tar czf $OUT/call3.tgz -C /tmp keep; echo "all: $(el) s"
