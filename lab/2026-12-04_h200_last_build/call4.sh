#!/usr/bin/env bash
# The targets with the session's last build (the blur in 64x4 and 4x64), 10
# interleaved repetitions, the clocks beside them, and ssdo_fast n16.
set -uo pipefail
. scripts/gpu_env.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
K=/tmp/keep; rm -rf $K; mkdir -p $K
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $K/gpu.txt 2>&1
filter='^corner/(alchemy_fast|hemisphere_fast)/n(16|32)/b4/full/1920x1080/(gl|vk)/compute/'
filter+='|^corner/(alchemy_fast|hemisphere_fast)/n16/b4/((fused_tail=1/)?half)/1920x1080/(gl|vk)/compute/'
filter+='|^corner/ssdo_fast/n16/b4/full/1920x1080/(gl|vk)/compute/'
smi_start $K/targets.clocks.csv
.bundle/run.sh --sweep gpu --benchmark_filter="$filter" --benchmark_repetitions=10 \
  --benchmark_enable_random_interleaving=true --max-time 0.3 \
  --benchmark_out=$K/targets.json --benchmark_out_format=json > $K/targets.txt 2> $K/targets.err
echo "== targets: rc $? ($(el) s)"; smi_stop
python3 lab/2026-12-04_h200_inexact_default/table.py $K/targets.json > $K/table.md 2>&1
cat $K/table.md
gzip -f $K/targets.json
tar czf $OUT/call4.tgz -C /tmp keep; echo "all: $(el) s"
