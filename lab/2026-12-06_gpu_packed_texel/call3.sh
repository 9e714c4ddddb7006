#!/usr/bin/env bash
# The launch probes alone, 10 repetitions, on whatever GPU is lent (for the
# H200's launch figures, where call1 ran on an H100), then launch_fit.py.
#   bash lab/2026-12-06_gpu_packed_texel/call3.sh   (.gl and .bundle carried)
set -uo pipefail
cd "$(dirname "$0")/../.."
. scripts/gpu_env.sh
start=$(date +%s)
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv > "$OUT/gpu3.csv" 2>&1
cat "$OUT/gpu3.csv"
filter='^timer/' reps=10 maxt=0.3 bench probes
python3 lab/2026-12-06_gpu_packed_texel/launch_fit.py "$OUT/probes.json" | tee "$OUT/launch3.md"
echo "all: $(( $(date +%s) - start )) s"
