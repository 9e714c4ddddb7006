#!/usr/bin/env bash
# The pyramid's texels carry their source pixel (RG32F): A = the build
# before (.bundle2, cavity_bench), B = this one (.bundle); then B against B
# with positionAt in fused multiply-adds and alchemy_fast's weight out of
# its sum (.old/v, --kernel-source); the gpu matrix rendered and judged.
set -uo pipefail
. scripts/gpu_env.sh
.bundle2/unpack.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
K=/tmp/keep; rm -rf $K; mkdir -p $K
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $K/gpu.txt 2>&1
filter='^corner/(alchemy_fast|hemisphere_fast)/n(16|32)/b4/((fused_tail=1/)?half|full)/1920x1080/(gl|vk)/compute/'
filter+='|^corner/ssdo_fast/n16/b4/full/1920x1080/(gl|vk)/compute/'
smi_start $K/ab.clocks.csv
.bundle/cavity.sh ab --a .bundle2 --b .bundle --rounds 4 --filter "$filter" \
  --bench-args='--sweep gpu --max-time 0.3' --out $K/ab > $K/ab.txt 2>&1
echo "== ab: rc $? ($(el) s)"; smi_stop
grep -E "n16/b4/.*compute +(pipeline|ao|pyramid|downsample|direct|indirect) " $K/ab.txt | cut -c1-125
f2='^corner/(alchemy_fast|hemisphere_fast)/n(16|32)/b4/full/1920x1080/(gl|vk)/compute/'
smi_start $K/fma.clocks.csv
.bundle/cavity.sh ab --a .bundle --b .bundle --rounds 4 --filter "$f2" \
  --bench-args='--sweep gpu --max-time 0.3' \
  --b-args="--kernel-source include/pyramid.glsl=$PWD/.old/v/pyramid_fma.glsl --kernel-source ssao_alchemy_fast.glsl=$PWD/.old/v/alchemy_fma.glsl" \
  --out $K/fma > $K/fma.txt 2>&1
echo "== fma ab: rc $? ($(el) s)"; smi_stop
grep -E "n(16|32)/b4/.*compute +(pipeline|ao) " $K/fma.txt | cut -c1-125
work=/tmp/refs; rm -rf $work; mkdir -p $work; cp -r baselines $work/base
smi_start $K/render.clocks.csv
.bundle/render.sh --matrix gpu --baselines $work/base --out $work/r0 > $K/render0.txt 2>&1
echo "== render: rc $? ($(el) s); image files: $(find $work/r0 -name '*.f32z' | wc -l)"; smi_stop
.bundle/cavity.sh gate judge $work/r0 --baselines $work/base --out $work/g0 --quiet > $K/judge.md 2>&1
echo "== judge: rc $? ($(el) s)"; head -3 $K/judge.md; cp $work/g0/gate.json $K/judge.json
cp $work/r0/manifest.json $K/render_manifest.json 2>/dev/null
tar czf $OUT/call1.tgz -C /tmp keep; echo "all: $(el) s"
