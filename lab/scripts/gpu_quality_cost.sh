#!/usr/bin/env bash
# Runs on the GPU machine (through the device tool), from the repo root, with
# .gl and the bundle carried: the inputs of `charts.py quality-cost`. Error
# against the ground truth at 1920x1080 (cavity_render quality, every AO
# kernel at the shared reach R = 0.5, corner and slats, full and half) and the
# AO passes' GPU time of every kernel x sample count x full/half on corner at
# 1920x1080 (cavity_bench, Vulkan, compute, blur 4). Each step has its own
# time limit so that what finished still comes back; everything is packed
# into $OUT/quality_cost.tgz (the device tool returns at most 8 files).
#   [BUNDLE=DIR] lab/scripts/gpu_quality_cost.sh [QUALITY_S] [BENCH_S]   (BUNDLE: default .bundle)
set -uo pipefail
cd "$(dirname "$0")/.."
. scripts/gpu_env.sh
qs="${1:-90}" bs="${2:-70}"
bundle="${BUNDLE:-.bundle}"
work=/tmp/quality_cost
rm -rf "$work"
mkdir -p "$work"
smi_start "$work/clocks.csv"
for res in full half; do
  timeout "$qs" "$bundle"/render.sh quality --backend vk --res 1920x1080 --scene corner,slats \
    --samples 4,8,16,32,64 --reach shared --resolution "$res" --out "$work/quality_$res" \
    > "$work/quality_$res.txt" 2>&1
  echo "quality $res: rc $? $(tail -1 "$work/quality_$res.txt")"
done
# Benchmark runs, each writes its JSON at its end: screen-space, then SDF in two halves.
i=0
for k in 'alchemy|alchemy_fast|hemisphere|hemisphere_cosine|hemisphere_fast|ssdo|ssdo_marched|ssdo_fast' 'sdf_classic|sdf_multiplicative|sdf_multiscale' \
         'sdf_jittered|sdf_hemisphere|sdf_fibonacci'; do
  timeout "$bs" "$bundle"/run.sh --sweep gpu --backend vk --max-time 0.5 \
    --benchmark_filter="^corner/($k)/n[0-9]+/b4/(full|half)/1920x1080/vk/compute" \
    --benchmark_out="$work/bench_$i.json" --benchmark_out_format=json > "$work/bench_$i.txt" 2> "$work/bench_$i.err"
  echo "bench $i: rc $? $(grep -c manual_time "$work/bench_$i.txt") lines"
  i=$((i + 1))
done
smi_stop
tar -C "$work" -czf "$OUT/quality_cost.tgz" .
ls -la "$work" "$OUT"
