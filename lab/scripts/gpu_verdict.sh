#!/usr/bin/env bash
# The timing-verdict check, in one call on the GPU machine (README, "Timing
# verdicts"): the unchanged build (A), a planted slowdown calibrated to +5% of
# the AO pass (B5), the unchanged build again (A/A), every pass +10% (B10, for
# the budgets) and the AO pass +2% (B2, if time allows), each run with the
# clocks sampled beside it. Leaves verdict.tgz in $OUT; judge it here with
# lab/scripts/verdict_table.py.
#   lab/scripts/gpu_verdict.sh [REPS (10)] [MAX_TIME_S (0.35)] [FILTER]
set -uo pipefail
cd "$(dirname "$0")/../.."
. scripts/gpu_env.sh
reps="${1:-10}"
maxt="${2:-0.35}"
filter="${3:-^corner/(alchemy|hemisphere)/n(16|32)/b4/(full|half)/1920x1080/(gl|vk)/compute/}"
start=$(date +%s)
elapsed() { echo $(( $(date +%s) - start )); }
calibrate() {   # out, passes, target, refinement points...
  local out=$1 passes=$2 target=$3; shift 3
  python3 lab/scripts/plant_calibrate.py "$OUT/a1.json" --point "512:$OUT/cal512.json" --point "2048:$OUT/cal2048.json" \
    --passes "$passes" --target "$target" "$@" > "$OUT/$out" 2>> "$OUT/calibration.log"
}
bench a1 || exit 1
# Dependent FMAs per pixel after a pass's kernel (kernels/assemble.cpp):
# their cost curve at 512 and 2048, one guess per target, one measured
# refinement of each guess, then the runs that are judged.
all=ao:512,blur:512,composite:512
reps=3 bench cal512 --plant "$all"
reps=3 bench cal2048 --plant "${all//512/2048}"
calibrate guess5.json ao 0.05 && calibrate guess10.json ao,blur,composite 0.10 || exit 1
reps=3 bench r5 --plant-file "$OUT/guess5.json"
reps=3 bench r10 --plant-file "$OUT/guess10.json"
calibrate plant5.json ao 0.05 --point-file "$OUT/guess5.json:$OUT/r5.json" &&
  calibrate plant10.json ao,blur,composite 0.10 --point-file "$OUT/guess10.json:$OUT/r10.json" &&
  calibrate plant2.json ao 0.02 --point-file "$OUT/guess5.json:$OUT/r5.json" || exit 1
bench b5 --plant-file "$OUT/plant5.json"
bench a2
bench b10 --plant-file "$OUT/plant10.json"
if [ "$(elapsed)" -lt 440 ]; then bench b2 --plant-file "$OUT/plant2.json"; fi
echo "== done ($(elapsed) s)"
cd "$OUT" && tar czf verdict.tgz ./*.json ./*.csv ./*.err ./*.txt ./*.log && rm -f ./*.json ./*.csv ./*.err ./*.txt ./*.log
ls -la "$OUT"
