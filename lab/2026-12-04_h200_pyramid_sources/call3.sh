#!/usr/bin/env bash
# pyramidLookup() testing the projected point against the image in floats
# and truncating (pyramid_lookup.glsl), where it clamped, floored and tested
# the texel: the same texels and verdicts. B against B with the edit, 4
# rounds; the gpu matrix's hemisphere_fast and ssdo_fast rendered with the
# edit and judged by digest.
set -uo pipefail
. scripts/gpu_env.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
K=/tmp/keep; rm -rf $K; mkdir -p $K
edit="include/pyramid.glsl=$PWD/.old/v/pyramid_lookup.glsl"
filter='^corner/hemisphere_fast/n(16|32)/b4/(full|fused_tail=1/half)/1920x1080/(gl|vk)/compute/'
filter+='|^corner/ssdo_fast/n16/b4/full/1920x1080/(gl|vk)/compute/'
smi_start $K/ab.clocks.csv
.bundle/cavity.sh ab --a .bundle --b .bundle --rounds 4 --filter "$filter" \
  --bench-args='--sweep gpu --max-time 0.3' --b-args="--kernel-source $edit" --out $K/ab > $K/ab.txt 2>&1
echo "== ab: rc $? ($(el) s)"; smi_stop
grep -E "compute +(pipeline|ao|direct|indirect) " $K/ab.txt | cut -c1-125
work=/tmp/refs; rm -rf $work; mkdir -p $work; cp -r baselines $work/base
.bundle/render.sh --matrix gpu --filter '/(hemisphere_fast|ssdo_fast)/' --kernel-source "$edit" --baselines $work/base --out $work/r0 > $K/render0.txt 2>&1
echo "== render: rc $? ($(el) s)"
.bundle/cavity.sh gate judge $work/r0 --baselines $work/base --out $work/g0 --quiet > $K/judge.md 2>&1
echo "== judge: rc $? ($(el) s)"; head -3 $K/judge.md; cp $work/g0/gate.json $K/judge.json
tar czf $OUT/call3.tgz -C /tmp keep; echo "all: $(el) s"
