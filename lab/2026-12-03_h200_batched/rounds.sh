#!/usr/bin/env bash
# The AO passes' sample loops (H200): the committed alchemy_fast (sample
# count compiled in, fetches issued in batches of 8, the layer branch
# compiled out at k = 1) against the kernel before it and against one
# change at a time; hemisphere_fast with its point count compiled in, with
# and without the early exit of a blocked ray, and batched as alchemy_fast
# (hemisphere_batched.glsl); every pass's workgroup
# reshaped (CAVITY_WORKGROUP), the composite an empty dispatch at three
# shapes (how much of a pass the launch is). corner n16 b4 full
# 1920x1080, compute, both APIs, batch timing, ROUNDS interleaved rounds.
#   lab/2026-12-03_h200_batched/rounds.sh [ROUNDS (3)]
# As run. The variants/*.glsl it names are kept as diffs: README.md says how
# to rebuild them.
set -uo pipefail
cd "$(dirname "$0")/../.."
. scripts/gpu_env.sh
rounds="${1:-3}"
work=/tmp/batched; rm -rf $work; mkdir -p $work
E=lab/2026-12-03_h200_batched/variants
A=ssao_alchemy_fast.glsl
H=ssao_hemisphere_fast.glsl
declare -A V K W
V[a_new]="";                                                  K[a_new]=alchemy_fast
V[a_old]="--kernel-source $A=$E/alchemy_old.glsl --kernel-source include/pyramid.glsl=$E/pyramid_old.glsl"; K[a_old]=alchemy_fast
V[a_unrolled]="--kernel-source $A=$E/alchemy_unrolled.glsl --kernel-source include/pyramid.glsl=$E/pyramid_old.glsl"; K[a_unrolled]=alchemy_fast
V[a_branch]="--kernel-source include/pyramid.glsl=$E/pyramid_old.glsl"; K[a_branch]=alchemy_fast
V[a_batch4]="--kernel-source $A=$E/alchemy_batch4.glsl";       K[a_batch4]=alchemy_fast
V[a_batch16]="--kernel-source $A=$E/alchemy_batch16.glsl";     K[a_batch16]=alchemy_fast
V[h_new]="";                                                  K[h_new]=hemisphere_fast
V[h_old]="--kernel-source $H=$E/hemisphere_old.glsl --kernel-source include/pyramid.glsl=$E/pyramid_old.glsl"; K[h_old]=hemisphere_fast
V[h_noskip]="--kernel-source $H=$E/hemisphere_noskip.glsl";   K[h_noskip]=hemisphere_fast
V[h_batched]="--kernel-source $H=$E/hemisphere_batched.glsl"; K[h_batched]=hemisphere_fast
for wg in 16x16 32x8 16x8; do V[a_wg$wg]=""; K[a_wg$wg]=alchemy_fast; W[a_wg$wg]=$wg; done
V[h_wg16x16]=""; K[h_wg16x16]=hemisphere_fast; W[h_wg16x16]=16x16
for wg in 8x8 16x16 32x32; do
  V[e_wg$wg]="--kernel-source composite.glsl=lab/scripts/gl_gap/composite_empty.glsl"; K[e_wg$wg]=alchemy_fast; W[e_wg$wg]=$wg
done
order=(a_new a_old a_unrolled a_branch a_batch4 a_batch16 a_wg16x16 a_wg32x8 a_wg16x8 e_wg8x8 e_wg16x16 e_wg32x32
       h_new h_old h_noskip h_batched h_wg16x16)
smi_start $work/clocks.csv
start=$(date +%s)
for round in $(seq 1 "$rounds"); do
  for v in $(printf '%s\n' "${order[@]}" | shuf); do
    d=$work/$v.r$round
    CAVITY_WORKGROUP="${W[$v]:-}" timeout 120 .bundle/render.sh --matrix gpu --filter "^corner/${K[$v]}/n16/b4/full/1920x1080/(gl|vk)/compute\$" \
      --max-noise 0.5 --max-time 1 ${V[$v]} --out $d > $d.log 2>&1
    echo "$v r$round rc $? ($(( $(date +%s) - start )) s) $(tail -1 $d.log)"
    find $d -type f ! -name manifest.json ! -name '*.digest' -delete
  done
done
smi_stop
tar -C $work -czf $OUT/batched.tgz .
