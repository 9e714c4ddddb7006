#!/usr/bin/env bash
# GTAO with the separable blur: the probe package gtao_separable
# (probe_separable/: the gtao package writing the fast kernels' ao_key and
# asking for blur = "separable") against gtao's 2D bilateral blur, corner
# n16 b4, full and half, 1920x1080, both APIs, compute; 10 interleaved
# repetitions.
#   BUNDLE_BINARIES=cavity_bench BUNDLE_KERNELS=lab/2026-12-05_gpu_gtao/probe_separable scripts/bundle.sh
#   bash lab/2026-12-05_gpu_gtao/call3.sh      (on the GPU machine, .gl and .bundle carried)
set -uo pipefail
cd "$(dirname "$0")/../.."
. scripts/gpu_env.sh
start=$(date +%s)
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv > "$OUT/gpu.csv" 2>&1
filter='^corner/(gtao|gtao_separable)/n16/b4/(full|half)/1920x1080/(gl|vk)/compute/'
reps=10 maxt=0.5
bench separable
awk '/^corner/ {id = $1} /median of/ {print id, $0}' "$OUT/separable.txt" > "$OUT/summary.txt"
gzip -9 "$OUT/separable.json"
tar -C "$OUT" -czf "$OUT/raw.tgz" separable.txt separable.err separable.clocks.csv && rm -f "$OUT"/separable.txt "$OUT"/separable.err "$OUT"/separable.clocks.csv
echo "done ($(( $(date +%s) - start )) s)"
cat "$OUT/summary.txt"
