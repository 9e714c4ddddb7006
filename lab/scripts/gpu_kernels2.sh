#!/usr/bin/env bash
# The fast kernels' new variants timed against their defaults on the GPU
# machine, in one call (docs/kernels.md): the one-dispatch depth pyramid
# against a dispatch per level (pyramid_per_level=1), the fused
# half-resolution tail (fused_tail=1) against upsample then composite, and
# the precision contract's --exact 1 (the CPU-exact arithmetic) and the interleaved layers
# (interleave=4, n16 and n32) against the defaults; 1920x1080,
# compute, both APIs, REPS repetitions interleaved in one process, the clocks
# sampled beside it; then the AO of each variant that changes it (--exact 1,
# --interleave 4) against the ground truth after the blur, corner and slats,
# n16 and n32. Leaves kernels2.tgz in $OUT; compare pairs here with
# `cavity compare --filter`, quality with the quality.json files.
#   lab/scripts/gpu_kernels2.sh [REPS (10)] [MAX_TIME_S (0.35)]
set -uo pipefail
cd "$(dirname "$0")/.."
. scripts/gpu_env.sh
reps="${1:-10}"
maxt="${2:-0.35}"
filter='^corner/(alchemy_fast|hemisphere_fast)/n(16|32)/b4/((exact=1|pyramid_per_level=1|interleave=4)/)?full/1920x1080/(gl|vk)/compute/'
filter+='|^corner/(alchemy|alchemy_fast|hemisphere_fast)/n16/b4/((fused_tail=1|interleave=4)/)?half/1920x1080/(gl|vk)/compute/'
smi_start "$OUT/clocks.csv"
.bundle/run.sh --sweep gpu --benchmark_filter="$filter" --benchmark_repetitions="$reps" \
  --benchmark_enable_random_interleaving=true --max-time "$maxt" \
  --benchmark_out="$OUT/kernels2.json" --benchmark_out_format=json > "$OUT/kernels2.txt" 2> "$OUT/kernels2.err"
echo "cavity_bench: exit $?"
smi_stop
# Quality held: each variant that changes the AO against the ground truth,
# after the blur, at the same samples, scenes and size.
for variant in "" "--exact 1" "--interleave 4"; do
  name=${variant:+$(echo "$variant" | tr -d '-' | tr ' ' '=')}
  name=${name:-default}
  for s in corner slats; do
    timeout 150 .bundle/render.sh quality --backend vk --res 1920x1080 --scene "$s" --kernel alchemy_fast,hemisphere_fast \
      --samples 16,32 --reach shared --blur 4 $variant --out "$OUT/quality_${name}_$s" > "$OUT/quality_${name}_$s.txt" 2>&1
    echo "quality $name $s: rc $? $(tail -1 "$OUT/quality_${name}_$s.txt")"
  done
done
cd "$OUT" && tar czf kernels2.tgz kernels2.json kernels2.txt kernels2.err clocks.csv quality_* &&
  rm -rf kernels2.json kernels2.txt kernels2.err clocks.csv quality_*
ls -la "$OUT"
