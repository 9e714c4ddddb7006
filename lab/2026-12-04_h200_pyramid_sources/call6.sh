#!/usr/bin/env bash
# hemisphere_fast's points four to an iteration on GL (hemisphere_by4.glsl;
# GL keeps a loop rolled), B against B+edit, 4 rounds; the gpu matrix's
# hemisphere_fast configurations rendered with it and judged by digest.
set -uo pipefail
. scripts/gpu_env.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
K=/tmp/keep; rm -rf $K; mkdir -p $K
edit="ssao_hemisphere_fast.glsl=$PWD/.old/v/hemisphere_by4.glsl"
filter='^corner/hemisphere_fast/n(16|32)/b4/(full|fused_tail=1/half)/1920x1080/(gl|vk)/compute/'
smi_start $K/ab.clocks.csv
.bundle/cavity.sh ab --a .bundle --b .bundle --rounds 4 --filter "$filter" \
  --bench-args='--sweep gpu --max-time 0.3' --b-args="--kernel-source $edit" --out $K/ab > $K/ab.txt 2>&1
echo "== ab: rc $? ($(el) s)"; smi_stop
grep -E "compute +(pipeline|ao) " $K/ab.txt | cut -c1-125
work=/tmp/refs; rm -rf $work; mkdir -p $work; cp -r baselines $work/base
.bundle/render.sh --matrix gpu --filter '/hemisphere_fast/' --kernel-source "$edit" --baselines $work/base --out $work/r0 > $K/render0.txt 2>&1
echo "== render: rc $? ($(el) s)"; grep "KiB" $K/render0.txt | grep -v " 0.0 KiB"
tar czf $OUT/call6.tgz -C /tmp keep; echo "all: $(el) s"
