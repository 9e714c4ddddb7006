#!/usr/bin/env bash
# GTAO at 1920x1080 beside the fast kernels it competes with, on the lent GPU:
# the gpu sweep's corner n16 b4 full configurations of gtao, alchemy_fast and
# hemisphere_fast, both APIs, compute, 10 interleaved repetitions, clocks
# sampled beside; then gtao at XeGTAO's "High" shape (3 slices, 3 steps a
# side: 18 samples) with cavity run, both APIs.
#   bash lab/2026-12-05_gpu_gtao/call1.sh   (on the GPU machine, .gl and .bundle carried)
set -uo pipefail
cd "$(dirname "$0")/../.."
. scripts/gpu_env.sh
start=$(date +%s)
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv > "$OUT/gpu.csv" 2>&1
filter='^corner/(gtao|alchemy_fast|hemisphere_fast)/n16/b4/(full|half)/1920x1080/(gl|vk)/compute/'
reps=10 maxt=0.5
bench targets
smi_start "$OUT/high.clocks.csv"
for api in vk gl; do
  .bundle/cavity.sh run --kernel gtao --samples 18 --slices 3 --blur 4 --backend "$api" --scene corner \
    --res 1920x1080 --frames 200 --out /tmp/high_$api > "$OUT/high_$api.txt" 2>&1
  cp /tmp/high_$api/results.json "$OUT/high_$api.json" 2>/dev/null
done
smi_stop
echo "done ($(( $(date +%s) - start )) s)"
tail -20 "$OUT/targets.txt"
grep -E "gtao .*(ao|frame) " "$OUT"/high_*.txt
