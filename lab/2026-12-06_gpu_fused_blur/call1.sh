#!/usr/bin/env bash
# The separable blur's two passes against one (fused_blur), alchemy_fast
# and hemisphere_fast n16 b4 at 1920x1080, full and half resolution with the
# fused tail, both APIs: 10 interleaved repetitions in one process, with
# the clocks beside them; then table.py.
#   bash lab/2026-12-06_gpu_fused_blur/call1.sh   (.gl and .bundle carried)
set -uo pipefail
cd "$(dirname "$0")/../.."
. scripts/gpu_env.sh
start=$(date +%s)
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv > "$OUT/gpu.csv" 2>&1
cat "$OUT/gpu.csv"
filter='^corner/(alchemy_fast|hemisphere_fast)/n16/b4/(fused_blur=1/)?(full|fused_tail=1/half)/1920x1080/(gl|vk)/compute/'
reps=10 maxt=0.3 bench fused
echo "fused: rc $? ($(( $(date +%s) - start )) s)"
python3 lab/2026-12-06_gpu_fused_blur/table.py "$OUT/fused.json" | tee "$OUT/table.md"
gzip -f "$OUT/fused.json"
echo "all: $(( $(date +%s) - start )) s"
