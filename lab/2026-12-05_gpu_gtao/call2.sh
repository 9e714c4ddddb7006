#!/usr/bin/env bash
# call1.sh's question again with fewer files back (the device tool returns
# eight): GTAO (2 slices, n16), the probe package gtao_high (XeGTAO's High:
# 3 slices, 3 steps a side, 18 depth taps; probe/, carried in the bundle by
# BUNDLE_KERNELS), alchemy_fast and hemisphere_fast, corner n16 b4, full and
# half, 1920x1080, both APIs, compute; 10 interleaved repetitions.
#   BUNDLE_BINARIES=cavity_bench BUNDLE_KERNELS=lab/2026-12-05_gpu_gtao/probe scripts/bundle.sh
#   bash lab/2026-12-05_gpu_gtao/call2.sh      (on the GPU machine, .gl and .bundle carried)
set -uo pipefail
cd "$(dirname "$0")/../.."
. scripts/gpu_env.sh
start=$(date +%s)
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv > "$OUT/gpu.csv" 2>&1
filter='^corner/(gtao|gtao_high|alchemy_fast|hemisphere_fast)/n16/b4/(full|half)/1920x1080/(gl|vk)/compute/'
reps=10 maxt=0.5
bench targets
awk '/^corner/ {id = $1} /median of/ {print id, $0}' "$OUT/targets.txt" > "$OUT/summary.txt"
gzip -9 "$OUT/targets.json"
tar -C "$OUT" -czf "$OUT/raw.tgz" targets.txt targets.err targets.clocks.csv && rm -f "$OUT"/targets.txt "$OUT"/targets.err "$OUT"/targets.clocks.csv
echo "done ($(( $(date +%s) - start )) s)"
cat "$OUT/summary.txt"
