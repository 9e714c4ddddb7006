#!/usr/bin/env bash
set -uo pipefail
. scripts/gpu_env.sh
.bundle2/unpack.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
K=/tmp/keep; rm -rf $K; mkdir -p $K
F='^corner/alchemy_fast/n16/b4/(fused_tail=1/)?half/1920x1080/(gl|vk)/compute/'
smi_start $K/clocks.csv
.bundle/cavity.sh ab --a .bundle --b .bundle --b-args="--kernel-source upsample_composite.glsl=lab/2026-12-04_h200_downsample_pyramid/quads_preload.glsl" --rounds 4 \
  --filter "$F" --bench-args='--sweep gpu --max-time 0.3' --out $K/ab_preload > $K/ab_preload.txt 2>&1
echo "== ab preload: rc $? ($(el) s)"
grep -E "compute +(pipeline|upsample_composite) " $K/ab_preload.txt | cut -c1-125
for wg in 8x8 16x8 8x16 16x16 32x8 32x4; do
  CAVITY_WORKGROUP=$wg .bundle2/run.sh --sweep gpu --benchmark_filter="$F" --benchmark_repetitions=5 \
    --benchmark_enable_random_interleaving=true --max-time 0.3 --benchmark_out=$K/wg_$wg.json --benchmark_out_format=json > $K/wg_$wg.txt 2>&1
  echo "== wg $wg: rc $? ($(el) s)"
done
smi_stop
tar czf $OUT/call2.tgz -C /tmp keep; echo "all: $(el) s"
