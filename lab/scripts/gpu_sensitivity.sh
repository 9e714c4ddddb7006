#!/usr/bin/env bash
# Small slowdowns on the GPU, in one call on the GPU machine (docs/comparing.md,
# "Do the verdicts hold on a GPU?"): the unchanged build (A1), the AO pass
# slowed by each TARGET (B<pct>, calibrated per configuration in two measured
# refinement rounds, since the first few hundred planted FMAs hide behind
# memory latency and the cost curve is steepest just where 1% lies), and the
# unchanged build again (A2). Every run is its own process with the clocks
# sampled beside it. Leaves sensitivity.tgz in $OUT; judge it here with
# lab/scripts/verdict_table.py.
#   lab/scripts/gpu_sensitivity.sh [REPS (10)] [MAX_TIME_S (0.35)] [TARGETS ("0.01 0.02")] [FILTER]
set -uo pipefail
cd "$(dirname "$0")/.."
. scripts/gpu_env.sh
reps="${1:-10}"
maxt="${2:-0.35}"
targets="${3:-0.01 0.02}"
filter="${4:-^corner/(alchemy|alchemy_fast|hemisphere|hemisphere_fast)/n16/b4/(full|half)/1920x1080/(gl|vk)/compute/}"
start=$(date +%s)
elapsed() { echo $(( $(date +%s) - start )); }
pct() { python3 -c "print(round(100 * $1))"; }
bench a1 || exit 1
bench cal512 --plant ao:512 --benchmark_repetitions=3
bench cal2048 --plant ao:2048 --benchmark_repetitions=3
for t in $targets; do
  p=$(pct "$t")
  points=(--point "512:$OUT/cal512.json" --point "2048:$OUT/cal2048.json")
  python3 lab/scripts/plant_calibrate.py "$OUT/a1.json" "${points[@]}" --passes ao --target "$t" \
    > "$OUT/guess${p}a.json" 2>> "$OUT/calibration.log" || exit 1
  for round in a b; do
    bench "r${p}${round}" --plant-file "$OUT/guess${p}${round}.json" --benchmark_repetitions=3
    points+=(--point-file "$OUT/guess${p}${round}.json:$OUT/r${p}${round}.json")
    next=$([ "$round" = a ] && echo "guess${p}b.json" || echo "plant${p}.json")
    python3 lab/scripts/plant_calibrate.py "$OUT/a1.json" "${points[@]}" --passes ao --target "$t" \
      > "$OUT/$next" 2>> "$OUT/calibration.log" || exit 1
  done
done
for t in $targets; do
  p=$(pct "$t")
  bench "b$p" --plant-file "$OUT/plant$p.json"
done
bench a2
echo "== done ($(elapsed) s)"
cd "$OUT" && tar czf sensitivity.tgz ./*.json ./*.csv ./*.err ./*.txt ./*.log &&
  rm -f ./*.json ./*.csv ./*.err ./*.txt ./*.log
ls -la "$OUT"
