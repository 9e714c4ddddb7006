#!/usr/bin/env bash
# Checks the GPU budgets of baselines/budgets.json on the GPU machine: the
# unchanged build (a1) must stay within them and a build with EVERY pass
# planted +10% (b10) must fail them pass by pass. The plant is calibrated as
# in gpu_verdict.sh, from cost curves at 64, 256 and 1024 FMAs and one
# measured refinement. Judge here: python3 lab/scripts/verdict_table.py DIR.
#   lab/scripts/gpu_budget_check.sh [REPS (5)] [MAX_TIME_S (0.35)] [FILTER]
set -uo pipefail
cd "$(dirname "$0")/.."
. scripts/gpu_env.sh
reps="${1:-5}"
maxt="${2:-0.35}"
filter="${3:-^corner/(alchemy|hemisphere)/n(16|32)/b4/(full|half)/1920x1080/(gl|vk)/compute/}"
passes=gbuffer,downsample,depth,ao,box,blur,upsample,composite
start=$(date +%s)
plant_all() { local n=$1; echo "$passes" | sed "s/\([a-z]*\)/\1:$n/g"; }
bench a1 || exit 1
for n in 64 256 1024; do bench "cal$n" --plant "$(plant_all $n)" --benchmark_repetitions=3; done
points=(--point "64:$OUT/cal64.json" --point "256:$OUT/cal256.json" --point "1024:$OUT/cal1024.json")
python3 lab/scripts/plant_calibrate.py "$OUT/a1.json" "${points[@]}" --passes "$passes" --target 0.10 \
  > "$OUT/guess10.json" 2>> "$OUT/calibration.log" || exit 1
bench r10 --plant-file "$OUT/guess10.json" --benchmark_repetitions=3
python3 lab/scripts/plant_calibrate.py "$OUT/a1.json" "${points[@]}" --point-file "$OUT/guess10.json:$OUT/r10.json" \
  --passes "$passes" --target 0.10 > "$OUT/plant10.json" 2>> "$OUT/calibration.log" || exit 1
bench b10 --plant-file "$OUT/plant10.json"
echo "== done ($(( $(date +%s) - start )) s)"
cd "$OUT" && tar czf budget_check.tgz ./*.json ./*.csv ./*.err ./*.txt ./*.log && rm -f ./*.json ./*.csv ./*.err ./*.txt ./*.log
