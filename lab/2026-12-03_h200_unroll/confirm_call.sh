#!/usr/bin/env bash
# alchemy_fast as committed last (Vulkan's loop, GL's samples written out),
# 10 interleaved repetitions.
set -uo pipefail
cd "$(dirname "$0")/.."
for f in .bundle/*.xz .bundle/lib/*.xz .bundle2/*.xz; do xz -d "$f"; done
cp .bundle2/cavity_bench .bundle/cavity_bench; chmod +x .bundle/cavity_bench
. scripts/gpu_env.sh
mkdir -p /tmp/keep
filter='^corner/alchemy_fast/n(16|32)/b4/((exact=0)/)?full/1920x1080/(gl|vk)/compute/|^corner/alchemy_fast/n16/b4/(fused_tail=1/)?half/1920x1080/(gl|vk)/compute/'
smi_start /tmp/keep/clocks.csv
.bundle/run.sh --sweep gpu --benchmark_filter="$filter" --benchmark_repetitions=10 \
  --benchmark_enable_random_interleaving=true --max-time 0.3 \
  --benchmark_out=/tmp/keep/confirm.json --benchmark_out_format=json > /tmp/keep/confirm.txt 2> /tmp/keep/confirm.err
echo "rc $?"
smi_stop
tar czf $OUT/confirm.tgz -C /tmp keep
