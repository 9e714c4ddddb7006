#!/usr/bin/env bash
# Narrow against full barriers on the GPU machine (through the device tool, .gl and
# .bundle carried): what the narrow barriers buy. The seed and fast
# pipelines at 1920x1080, both APIs, compute stage, timed with the narrow
# barriers and with CAVITY_FULL_BARRIERS=1 (README, "Synchronisation between
# passes"), alternating narrow, full, narrow, full in separate processes, 5
# interleaved repetitions each, clocks sampled beside them. Leaves sync.tgz
# in $OUT; compare with lab/scripts/sync_table.py.
#   lab/scripts/gpu_sync.sh [REPS (5)] [MAX_TIME_S (0.25)]
set -uo pipefail
cd "$(dirname "$0")/.."
. scripts/gpu_env.sh
reps="${1:-5}" maxt="${2:-0.25}"
work=/tmp/sync
rm -rf "$work"
mkdir -p "$work"
filter='^corner/(alchemy|alchemy_fast|hemisphere_fast)/n16/b4/(full|half)/1920x1080/(gl|vk)/compute/|^corner/ssdo_fast/n16/b4/full/1920x1080/(gl|vk)/compute/'
start=$(date +%s)
for round in 1 2; do
  for mode in narrow full; do
    name="${mode}_$round"
    echo "== $name ($(( $(date +%s) - start )) s)"
    smi_start "$work/$name.clocks.csv"
    if [ "$mode" = full ]; then export CAVITY_FULL_BARRIERS=1; else unset CAVITY_FULL_BARRIERS; fi
    .bundle/run.sh --sweep gpu --benchmark_filter="$filter" --benchmark_repetitions="$reps" \
      --benchmark_enable_random_interleaving=true --max-time "$maxt" \
      --benchmark_out="$work/$name.json" --benchmark_out_format=json > "$work/$name.txt" 2> "$work/$name.err"
    echo "rc $? $(tail -1 "$work/$name.err")"
    smi_stop
  done
done
unset CAVITY_FULL_BARRIERS
tar -C "$work" -czf "$OUT/sync.tgz" .
ls -la "$OUT"
