#!/usr/bin/env bash
# The session's last build on the H200, in one call:
# 1. Two probes by --kernel-source, each cavity ab's B against B, 4 rounds:
#    hemisphere_fast with four rays an iteration on GL (hemisphere_rays4.glsl),
#    and the downsample's pick with its three texels written out
#    (downsample_written.glsl, include/downsample.glsl).
# 2. The targets, 10 interleaved repetitions, the clocks beside them, and
#    ssdo_fast n16.
set -uo pipefail
. scripts/gpu_env.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
D=lab/2026-12-04_h200_last_build
K=/tmp/keep; rm -rf $K; mkdir -p $K
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $K/gpu.txt 2>&1
probe() {   # NAME FILTER KERNEL_SOURCE
  smi_start $K/ab_$1.clocks.csv
  .bundle/cavity.sh ab --a .bundle --b .bundle --rounds 4 --filter "$2" \
    --bench-args='--sweep gpu --max-time 0.3' --b-args="--kernel-source $3" --out $K/ab_$1 > $K/ab_$1.txt 2>&1
  echo "== ab $1: rc $? ($(el) s)"; smi_stop
}
probe rays4 '^corner/hemisphere_fast/n(16|32)/b4/full/1920x1080/gl/compute/|^corner/hemisphere_fast/n16/b4/fused_tail=1/half/1920x1080/gl/compute/' \
  ssao_hemisphere_fast.glsl=$D/hemisphere_rays4.glsl
grep -E "compute +ao " $K/ab_rays4.txt | cut -c1-140
probe downsample '^corner/(alchemy_fast|hemisphere_fast)/n16/b4/(fused_tail=1/)?half/1920x1080/(gl|vk)/compute/' \
  include/downsample.glsl=$D/downsample_written.glsl
grep -E "compute +(downsample|pipeline) " $K/ab_downsample.txt | cut -c1-140
filter='^corner/(alchemy_fast|hemisphere_fast)/n(16|32)/b4/full/1920x1080/(gl|vk)/compute/'
filter+='|^corner/(alchemy_fast|hemisphere_fast)/n16/b4/((fused_tail=1/)?half)/1920x1080/(gl|vk)/compute/'
filter+='|^corner/ssdo_fast/n16/b4/full/1920x1080/(gl|vk)/compute/'
smi_start $K/targets.clocks.csv
.bundle/run.sh --sweep gpu --benchmark_filter="$filter" --benchmark_repetitions=10 \
  --benchmark_enable_random_interleaving=true --max-time 0.3 \
  --benchmark_out=$K/targets.json --benchmark_out_format=json > $K/targets.txt 2> $K/targets.err
echo "== targets: rc $? ($(el) s)"; smi_stop
python3 lab/2026-12-04_h200_inexact_default/table.py $K/targets.json > $K/table.md 2>&1
head -14 $K/table.md
gzip -f $K/targets.json
tar czf $OUT/call1.tgz -C /tmp keep; echo "all: $(el) s"
