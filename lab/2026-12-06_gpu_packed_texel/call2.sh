#!/usr/bin/env bash
# The fast pipelines timed two ways on each API: the sum of the passes'
# own scopes (the benchmark's time) and one scope around the whole
# (pipeline_one_scope_ms), 10 interleaved repetitions, with the clocks
# beside them; then onescope.py's table: GL over Vulkan each way.
#   bash lab/2026-12-06_gpu_packed_texel/call2.sh   (.gl and .bundle carried)
set -uo pipefail
cd "$(dirname "$0")/../.."
. scripts/gpu_env.sh
start=$(date +%s)
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv > "$OUT/gpu2.csv" 2>&1
cat "$OUT/gpu2.csv"
filter='^corner/(alchemy_fast|hemisphere_fast)/n16/b4/(full|fused_tail=1/half)/1920x1080/(gl|vk)/compute/'
filter+='|^corner/alchemy_fast/n32/b4/full/1920x1080/(gl|vk)/compute/|^corner/(ssdo_fast|gtao)/n16/b4/full/1920x1080/(gl|vk)/compute/'
reps=10 maxt=0.3 bench onescope
echo "onescope: rc $? ($(( $(date +%s) - start )) s)"
python3 lab/2026-12-06_gpu_packed_texel/onescope.py "$OUT/onescope.json" | tee "$OUT/onescope.md"
gzip -f "$OUT/onescope.json"
echo "all: $(( $(date +%s) - start )) s"
