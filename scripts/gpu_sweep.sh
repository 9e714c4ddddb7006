#!/usr/bin/env bash
# Runs on the GPU machine (through the device tool), from the repo root, with
# .gl and .bundle carried: records the clocks and runs the full benchmark
# sweep, leaving everything in $OUT.
#   scripts/gpu_sweep.sh [extra cavity_bench flags]
set -uo pipefail
cd "$(dirname "$0")/.."
. scripts/gpu_env.sh
smi_start "$OUT/clocks.csv"
.bundle/run.sh --sweep gpu --benchmark_out="$OUT/gpu_sweep.json" --benchmark_out_format=json "$@" \
  > "$OUT/gpu_sweep.txt" 2> "$OUT/gpu_sweep.err"
rc=$?
smi_stop
tail -5 "$OUT/gpu_sweep.txt"; tail -5 "$OUT/gpu_sweep.err"
exit $rc
