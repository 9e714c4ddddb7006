#!/usr/bin/env bash
# ssdo_fast with its direction count and points a direction compiled in, on
# the H200, in one call:
# 1. cavity ab, 4 rounds, A = the build before (.bundle2), B = this one.
# 2. cavity ab, 4 rounds, B against B with the direct pass's directions
#    unrolled as well (direct_unrolled.glsl, by --kernel-source).
# 3. The gpu matrix's ssdo_fast pipelines rendered and judged by digest.
set -uo pipefail
. scripts/gpu_env.sh
.bundle2/unpack.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
D=lab/2026-12-04_h200_ssdo_compiled
K=/tmp/keep; rm -rf $K; mkdir -p $K
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $K/gpu.txt 2>&1
filter='^corner/ssdo_fast/n(8|16|32)/b4/full/1920x1080/(gl|vk)/compute/'
smi_start $K/ab.clocks.csv
.bundle/cavity.sh ab --a .bundle2 --b .bundle --rounds 4 --filter "$filter" \
  --bench-args='--sweep gpu --max-time 0.3' --out $K/ab > $K/ab.txt 2>&1
echo "== ab: rc $? ($(el) s)"; smi_stop
grep -E "compute +(direct|indirect|pipeline) " $K/ab.txt | cut -c1-140
smi_start $K/ab_unrolled.clocks.csv
.bundle/cavity.sh ab --a .bundle --b .bundle --rounds 4 --filter "$filter" \
  --bench-args='--sweep gpu --max-time 0.3' --b-args="--kernel-source ssdo_fast_direct.glsl=$D/direct_unrolled.glsl" \
  --out $K/ab_unrolled > $K/ab_unrolled.txt 2>&1
echo "== ab unrolled: rc $? ($(el) s)"; smi_stop
grep -E "compute +(direct|pipeline) " $K/ab_unrolled.txt | cut -c1-140
work=/tmp/refs; rm -rf $work; mkdir -p $work; cp -r baselines $work/base
.bundle/render.sh --matrix gpu --filter '/ssdo_fast/' --baselines $work/base --out $work/r > $K/render.txt 2>&1
echo "== render: rc $? ($(el) s)"
.bundle/cavity.sh gate judge $work/r --baselines $work/base --out $work/g --quiet > $K/judge.md 2>&1
echo "== judge: rc $?"; head -3 $K/judge.md
tar czf $OUT/call1.tgz -C /tmp keep; echo "all: $(el) s"
