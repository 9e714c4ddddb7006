#!/usr/bin/env bash
# The targets with the session's last build, 10 interleaved repetitions, the
# clocks beside them.
set -uo pipefail
. scripts/gpu_env.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $OUT/gpu.txt 2>&1
filter='^corner/(alchemy_fast|hemisphere_fast)/n(16|32)/b4/full/1920x1080/(gl|vk)/compute/'
filter+='|^corner/(alchemy_fast|hemisphere_fast)/n16/b4/((fused_tail=1/)?half)/1920x1080/(gl|vk)/compute/'
smi_start $OUT/targets.clocks.csv
.bundle/run.sh --sweep gpu --benchmark_filter="$filter" --benchmark_repetitions=10 \
  --benchmark_enable_random_interleaving=true --max-time 0.3 \
  --benchmark_out=$OUT/targets.json --benchmark_out_format=json > $OUT/targets.txt 2> $OUT/targets.err
echo "== targets: rc $? ($(el) s)"; smi_stop
gzip -f $OUT/targets.json; echo "all: $(el) s"
