#!/usr/bin/env bash
set -uo pipefail
. scripts/gpu_env.sh
.bundle2/unpack.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
K=/tmp/keep; rm -rf $K; mkdir -p $K
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $K/gpu.txt 2>&1
smi_start $K/ab.clocks.csv
.bundle/cavity.sh ab --a .bundle2 --b .bundle --rounds 4 \
  --filter '^corner/(alchemy_fast|hemisphere_fast)/n16/b4/((fused_tail=1/)?half|full)/1920x1080/(gl|vk)/compute/' \
  --bench-args='--sweep gpu --max-time 0.3' --out $K/ab > $K/ab.txt 2>&1
echo "== ab: rc $? ($(el) s)"
grep -E "compute +(pipeline|upsample|upsample_composite) " $K/ab.txt | cut -c1-125
.bundle/cavity.sh ab --a .bundle --b .bundle --b-args="--kernel-source upsample_composite=lab/2026-12-04_h200_downsample_pyramid/quads_preload.glsl" --rounds 4 \
  --filter '^corner/alchemy_fast/n16/b4/fused_tail=1/half/1920x1080/(gl|vk)/compute/' \
  --bench-args='--sweep gpu --max-time 0.3' --out $K/ab_preload > $K/ab_preload.txt 2>&1
echo "== ab preload: rc $? ($(el) s)"; smi_stop
grep -E "compute +(pipeline|upsample_composite) " $K/ab_preload.txt | cut -c1-125
work=/tmp/refs; rm -rf $work; mkdir -p $work; cp -r baselines $work/base
.bundle/render.sh --matrix gpu --filter '/half/' --baselines $work/base --out $work/r0 > $K/render0.txt 2>&1
echo "== render: rc $? ($(el) s); image files: $(find $work/r0 -name '*.f32z' | wc -l)"
.bundle/cavity.sh gate judge $work/r0 --baselines $work/base --out $work/g0 --quiet > $K/judge.md 2>&1
echo "== judge: rc $? ($(el) s)"; head -3 $K/judge.md; cp $work/g0/gate.json $K/judge.json
tar czf $OUT/call1.tgz -C /tmp keep; echo "all: $(el) s"
