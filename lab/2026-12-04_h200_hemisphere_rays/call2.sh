#!/usr/bin/env bash
# The committed form: hemisphere_fast with its rays' shape compiled in
# (samples and steps), on the H200, in one call:
# 1. cavity ab, 4 rounds, A = the build before (.bundle2), B = this one, the
#    fast kernels' targets configurations.
# 2. The targets, 10 interleaved repetitions, the clocks beside them.
# 3. The gpu matrix's hemisphere_fast pipelines rendered and judged by digest
#    against the approved ones.
set -uo pipefail
. scripts/gpu_env.sh
.bundle2/unpack.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
K=/tmp/keep; rm -rf $K; mkdir -p $K
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $K/gpu.txt 2>&1
filter='^corner/(alchemy_fast|hemisphere_fast)/n(16|32)/b4/full/1920x1080/(gl|vk)/compute/'
filter+='|^corner/(alchemy_fast|hemisphere_fast)/n16/b4/((fused_tail=1/)?half)/1920x1080/(gl|vk)/compute/'
smi_start $K/ab.clocks.csv
.bundle/cavity.sh ab --a .bundle2 --b .bundle --rounds 4 --filter "$filter" \
  --bench-args='--sweep gpu --max-time 0.3' --out $K/ab > $K/ab.txt 2>&1
echo "== ab: rc $? ($(el) s)"; smi_stop
grep -E "compute +(ao|pipeline) " $K/ab.txt | cut -c1-140
smi_start $K/targets.clocks.csv
.bundle/run.sh --sweep gpu --benchmark_filter="$filter" --benchmark_repetitions=10 \
  --benchmark_enable_random_interleaving=true --max-time 0.3 \
  --benchmark_out=$K/targets.json --benchmark_out_format=json > $K/targets.txt 2> $K/targets.err
echo "== targets: rc $? ($(el) s)"; smi_stop
python3 lab/2026-12-04_h200_inexact_default/table.py $K/targets.json | head -14
gzip -f $K/targets.json
work=/tmp/refs; rm -rf $work; mkdir -p $work; cp -r baselines $work/base
.bundle/render.sh --matrix gpu --filter '/hemisphere_fast/' --baselines $work/base --out $work/r > $K/render.txt 2>&1
echo "== render: rc $? ($(el) s)"
.bundle/cavity.sh gate judge $work/r --baselines $work/base --out $work/g --quiet > $K/judge.md 2>&1
echo "== judge: rc $?"; head -3 $K/judge.md
tar czf $OUT/call2.tgz -C /tmp keep; echo "all: $(el) s"
