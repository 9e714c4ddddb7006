#!/usr/bin/env bash
# The fast kernels' new variants timed against their defaults on the GPU
# machine, in one call (docs/kernels.md): the one-dispatch depth pyramid
# against a dispatch per level (pyramid_per_level=1), the fused
# half-resolution tail (fused_tail=1) against upsample then composite, and
# the precision contract's --exact 0 against the exact default; 1920x1080,
# compute, both APIs, REPS repetitions interleaved in one process, the clocks
# sampled beside it. Leaves kernels2.tgz in $OUT; compare pairs here with
# `cavity compare --filter`.
#   scripts/gpu_kernels2.sh [REPS (10)] [MAX_TIME_S (0.35)]
set -uo pipefail
cd "$(dirname "$0")/.."
. scripts/gpu_env.sh
reps="${1:-10}"
maxt="${2:-0.35}"
filter='^corner/(alchemy_fast|hemisphere_fast)/n16/b4/((exact=0|pyramid_per_level=1)/)?full/1920x1080/(gl|vk)/compute/'
filter+='|^corner/(alchemy|alchemy_fast|hemisphere_fast)/n16/b4/(fused_tail=1/)?half/1920x1080/(gl|vk)/compute/'
smi_start "$OUT/clocks.csv"
.bundle/run.sh --sweep gpu --benchmark_filter="$filter" --benchmark_repetitions="$reps" \
  --benchmark_enable_random_interleaving=true --max-time "$maxt" \
  --benchmark_out="$OUT/kernels2.json" --benchmark_out_format=json > "$OUT/kernels2.txt" 2> "$OUT/kernels2.err"
echo "cavity_bench: exit $?"
smi_stop
cd "$OUT" && tar czf kernels2.tgz kernels2.json kernels2.txt kernels2.err clocks.csv &&
  rm -f kernels2.json kernels2.txt kernels2.err clocks.csv
ls -la "$OUT"
