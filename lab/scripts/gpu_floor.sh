#!/usr/bin/env bash
# The fast kernels against their floor on the GPU machine (through the device tool, .gl
# and .bundle carried), in parts so that each call stays under the device's
# 10 minutes:
#   bench:   the fast pipelines (alchemy_fast, hemisphere_fast at n16 and
#            n32, full and half; ssdo_fast at n16, full) beside the seed and
#            fixed ones they replace (alchemy, hemisphere_cosine, ssdo,
#            ssdo_marched), 1920x1080, both APIs, compute stage, 10
#            interleaved repetitions each, clocks sampled beside them; then
#            the fast kernels' fragment stage;
#   quality: the AO of the fast kernels and the ones they replace against
#            the ground truth at 1920x1080, raw and after the blur (cavity
#            quality --blur 0 and 4, the shared reach);
#   render:  the gpu-cpu gate matrix's fast configurations rendered here, to
#            judge against the lavapipe baselines.
# Leaves floor.tgz in $OUT; read it here with scripts/charts/floor_table.py.
#   lab/scripts/gpu_floor.sh [PARTS ("bench quality render")] [REPS (10)] [MAX_TIME_S (0.25)]
set -uo pipefail
cd "$(dirname "$0")/.."
. scripts/gpu_env.sh
parts=" ${1:-bench quality render} " reps="${2:-10}" maxt="${3:-0.25}"
work=/tmp/floor
rm -rf "$work"
mkdir -p "$work"
start=$(date +%s)
run_bench() {   # name, filter, extra flags...
  local name=$1 filter=$2; shift 2
  echo "== $name ($(( $(date +%s) - start )) s)"
  smi_start "$work/$name.clocks.csv"
  .bundle/run.sh --sweep gpu --benchmark_filter="$filter" --benchmark_repetitions="$reps" \
    --benchmark_enable_random_interleaving=true --max-time "$maxt" \
    --benchmark_out="$work/$name.json" --benchmark_out_format=json "$@" > "$work/$name.txt" 2> "$work/$name.err"
  echo "rc $? $(tail -1 "$work/$name.err")"
  smi_stop
}
if [[ $parts == *" bench "* ]]; then
  run_bench compute '^corner/(alchemy_fast|hemisphere_fast)/n(16|32)/b4/(full|half)/1920x1080/(gl|vk)/compute/|^corner/(alchemy|hemisphere_cosine)/n16/b4/(full|half)/1920x1080/(gl|vk)/compute/|^corner/(ssdo|ssdo_marched|ssdo_fast)/n16/b4/full/1920x1080/(gl|vk)/compute/'
  run_bench fragment '^corner/(alchemy_fast|hemisphere_fast|ssdo_fast)/n16/b4/full/1920x1080/(gl|vk)/fragment/'
fi
if [[ $parts == *" quality "* ]]; then
  for b in 0 4; do
    for s in corner slats; do
      timeout 150 .bundle/render.sh quality --backend vk --res 1920x1080 --scene "$s" \
        --kernel alchemy,alchemy_fast,hemisphere_cosine,hemisphere_fast,ssdo_marched,ssdo_fast \
        --samples 16,32 --reach shared --blur "$b" --out "$work/quality_${s}_b$b" > "$work/quality_${s}_b$b.txt" 2>&1
      echo "quality $s blur $b: rc $? $(tail -1 "$work/quality_${s}_b$b.txt")"
    done
  done
fi
if [[ $parts == *" render "* ]]; then
  timeout 150 .bundle/render.sh --matrix gpu-cpu --filter '(hemisphere_fast|ssdo_fast)/' --out "$work/render_gpu_cpu" > "$work/render_gpu_cpu.txt" 2>&1
  echo "render gpu-cpu fast kernels: rc $? $(tail -1 "$work/render_gpu_cpu.txt")"
fi
nvidia-smi -q > "$work/nvidia-smi.txt" 2>&1
tar -C "$work" -czf "$OUT/floor.tgz" .
ls -la "$OUT"
