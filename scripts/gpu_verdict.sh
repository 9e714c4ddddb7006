#!/usr/bin/env bash
# The timing-verdict check, in one call on the GPU machine (README, "Timing
# verdicts"): the unchanged build twice (A/A), a calibration run, and the
# build with a planted slowdown of the AO pass calibrated to +5% and +2%
# (A/B), each with the clocks sampled beside it. Judge the files it leaves
# in $OUT with scripts/verdict_table.py here.
#   scripts/gpu_verdict.sh [REPS (10)] [MAX_TIME_S (0.5)] [FILTER]
set -uo pipefail
cd "$(dirname "$0")/.."
. scripts/gpu_env.sh
reps="${1:-10}"
maxt="${2:-0.5}"
filter="${3:-^corner/(alchemy|hemisphere)/n(16|32)/b4/(full|half)/1920x1080/(gl|vk)/compute/}"
start=$(date +%s)
bench() {   # name, extra flags...
  local name=$1; shift
  echo "== $name ($(( $(date +%s) - start )) s)"
  smi_start "$OUT/$name.clocks.csv"
  .bundle/run.sh --sweep gpu --benchmark_filter="$filter" --benchmark_repetitions="$reps" \
    --benchmark_enable_random_interleaving=true --max-time "$maxt" \
    --benchmark_out="$OUT/$name.json" --benchmark_out_format=json "$@" > "$OUT/$name.txt" 2> "$OUT/$name.err"
  local rc=$?
  smi_stop
  tail -2 "$OUT/$name.err"
  return $rc
}
bench a1 || exit 1
bench a2
# Planted dependent FMAs per pixel after the AO kernel: measure the cost of
# 256 once, then plant the count that costs +5% (+2%) of each configuration's AO pass.
bench cal --plant ao:256 --benchmark_repetitions=3
python3 scripts/plant_calibrate.py "$OUT/a1.json" "$OUT/cal.json" --fmas 256 --target 0.05 > "$OUT/plant5.json" || exit 1
python3 scripts/plant_calibrate.py "$OUT/a1.json" "$OUT/cal.json" --fmas 256 --target 0.02 > "$OUT/plant2.json" || exit 1
bench b5 --plant-file "$OUT/plant5.json"
if [ $(( $(date +%s) - start )) -lt 400 ]; then bench b2 --plant-file "$OUT/plant2.json"; fi
echo "== done ($(( $(date +%s) - start )) s)"
cd "$OUT" && tar czf verdict.tgz ./*.json ./*.csv ./*.err ./*.txt && rm -f ./*.json ./*.csv ./*.err ./*.txt
ls -la "$OUT"
