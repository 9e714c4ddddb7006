#!/usr/bin/env bash
# Runs on the GPU machine (through the device tool), from the repo root, with
# .gl and .bundle carried: the inputs of `charts.py quality-cost`. Error
# against the ground truth at 1920x1080 (cavity_render quality, every AO
# kernel at the shared reach R = 0.5, corner and slats, full and half) and the
# AO passes' GPU time of every kernel x sample count x full/half on corner at
# 1920x1080 (cavity_bench, Vulkan, compute, blur 4). Each step has its own
# time limit so that what finished still comes back.
#   scripts/gpu_quality_cost.sh [QUALITY_S] [BENCH_S]
set -uo pipefail
cd "$(dirname "$0")/.."
. scripts/gpu_env.sh
qs="${1:-150}" bs="${2:-140}"
smi_start "$OUT/clocks.csv"
for res in full half; do
  timeout "$qs" .bundle/render.sh quality --backend vk --res 1920x1080 --scene corner,slats \
    --samples 4,8,16,32,64 --reach shared --resolution "$res" --out "$OUT/quality_$res" \
    > "$OUT/quality_$res.txt" 2>&1
  echo "quality $res: rc $?"; tail -2 "$OUT/quality_$res.txt"
done
# Two benchmark runs, each writes its JSON at its end: screen-space, then SDF.
i=0
for k in 'alchemy|hemisphere|hemisphere_cosine|ssdo' 'sdf_[a-z]+'; do
  timeout "$bs" .bundle/run.sh --sweep gpu --backend vk --max-time 0.5 \
    --benchmark_filter="^corner/($k)/n[0-9]+/b4/(full|half)/1920x1080/vk/compute" \
    --benchmark_out="$OUT/bench_$i.json" --benchmark_out_format=json > "$OUT/bench_$i.txt" 2> "$OUT/bench_$i.err"
  echo "bench $i: rc $?"; tail -2 "$OUT/bench_$i.txt"; tail -2 "$OUT/bench_$i.err"
  i=$((i + 1))
done
smi_stop
