#!/usr/bin/env bash
# Issue 10's measurement, in one call on the GPU machine (through the device
# tool, .gl and .bundle carried): the seed and fast Alchemy pipelines at
# n16 and n32 and the hemisphere ones (seed, cosine, fast) at n16 and the
# fast one at n32, 1920x1080, full and half, both APIs, 10 interleaved
# repetitions each, with the clocks sampled beside them; the fast kernels'
# fragment stage; then the AO of the seed and fast kernels against the
# ground truth at 1920x1080, raw and after the blur (cavity quality --blur 0
# and 4, the shared reach); and the gpu-cpu gate matrix's hemisphere_fast
# configurations rendered here, to judge against the lavapipe baselines.
# Leaves floor.tgz in $OUT; read it here with scripts/floor_table.py.
#   scripts/gpu_floor.sh [REPS (10)] [MAX_TIME_S (0.25)]
set -uo pipefail
cd "$(dirname "$0")/.."
. scripts/gpu_env.sh
reps="${1:-10}" maxt="${2:-0.25}"
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
run_bench compute '^corner/(alchemy|alchemy_fast|hemisphere_fast)/n(16|32)/b4/(full|half)/1920x1080/(gl|vk)/compute/|^corner/(hemisphere|hemisphere_cosine)/n16/b4/(full|half)/1920x1080/(gl|vk)/compute/'
run_bench fragment '^corner/(alchemy|alchemy_fast|hemisphere_cosine|hemisphere_fast)/n16/b4/(full|half)/1920x1080/(gl|vk)/fragment/'
for b in 0 4; do
  for s in corner slats; do
    timeout 120 .bundle/render.sh quality --backend vk --res 1920x1080 --scene "$s" \
      --kernel alchemy,alchemy_fast,hemisphere_cosine,hemisphere_fast \
      --samples 16,32 --reach shared --blur "$b" --out "$work/quality_${s}_b$b" > "$work/quality_${s}_b$b.txt" 2>&1
    echo "quality $s blur $b: rc $? $(tail -1 "$work/quality_${s}_b$b.txt")"
  done
done
timeout 120 .bundle/render.sh --matrix gpu-cpu --filter hemisphere_fast --out "$work/render_gpu_cpu" > "$work/render_gpu_cpu.txt" 2>&1
echo "render gpu-cpu hemisphere_fast: rc $? $(tail -1 "$work/render_gpu_cpu.txt")"
nvidia-smi -q > "$work/nvidia-smi.txt" 2>&1
tar -C "$work" -czf "$OUT/floor.tgz" .
ls -la "$OUT"
