#!/usr/bin/env bash
# call1.sh's targets again, everything in one archive: the device tool
# brings back at most eight files, and call1's JSON and clocks were among
# those left out (its floors.md and the printed launch fit came back).
#   bash lab/2026-12-06_gpu_round3/call2.sh   (.gl and .bundle carried)
set -uo pipefail
cd "$(dirname "$0")/../.."
. scripts/gpu_env.sh
start=$(date +%s)
K=/tmp/keep; rm -rf $K; mkdir -p $K
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv > $K/gpu.csv 2>&1
cat $K/gpu.csv
f='^corner/(alchemy_fast|hemisphere_fast|gtao)/n16/b4/(full|fused_tail=1/half)/1920x1080/(gl|vk)/compute/'
f+='|^corner/alchemy_fast/n32/b4/full/1920x1080/(gl|vk)/compute/|^corner/ssdo_fast/n16/b4/full/1920x1080/(gl|vk)/compute/'
filter="$f|^timer/" reps=10 maxt=0.3 OUT=$K bench targets
echo "targets: rc $? ($(( $(date +%s) - start )) s)"
python3 lab/2026-12-04_h200_floors/floors.py $K/targets.json > $K/floors.md 2>&1
python3 lab/2026-12-06_gpu_packed_texel/launch_fit.py $K/targets.json > $K/launch.md 2>&1; tail -3 $K/launch.md
grep -E "ssdo_fast|hemisphere_fast/n16/fused" $K/floors.md
gzip -f $K/targets.json $K/targets.clocks.csv
tar -C /tmp -czf "$OUT/call2.tgz" keep; ls -la "$OUT"; echo "all: $(( $(date +%s) - start )) s"
