#!/usr/bin/env bash
# The sixth call: the fast kernels as committed in 789e4a0 ("new": in
# alchemy_fast the split written out, pyramidTexel's tiny path through
# sourcePixel) against the pyramidTexel form first tried ("B") and
# c096d07's sources ("old"), corner n16 b4 full 1920x1080 compute, both
# APIs, each its own cavity_render process, ROUNDS shuffled rounds. As run,
# from a tree where .old/ held the other sources:
#   mkdir .old; git show 914f511:kernels/include/pyramid.glsl > .old/pyramid.glsl
#   git show 914f511:kernels/ssao_alchemy_fast.glsl > .old/alchemy_fast.glsl
#   (B: the working tree of ab_call.sh's call, as .old/pyramid_B.glsl and
#   .old/alchemy_fast_B.glsl)
#   lab/2026-12-03_h200_overheads/ab3_call.sh [ROUNDS]   (carry .old)
set -uo pipefail
cd "$(dirname "$0")/../.."
. scripts/gpu_env.sh
work=$(mktemp -d); start=$(date +%s)
smi_start "$work/clocks.csv"
for r in $(seq 1 "$1"); do
  for v in $(printf 'new\nold\nB\n' | shuf); do
    for k in alchemy_fast hemisphere_fast; do
      case $v in
        new) src=() ;;
        old) src=(--kernel-source include/pyramid.glsl=.old/pyramid.glsl); [ $k = alchemy_fast ] && src+=(--kernel-source ssao_alchemy_fast.glsl=.old/alchemy_fast.glsl) ;;
        B) src=(--kernel-source include/pyramid.glsl=.old/pyramid_B.glsl); [ $k = alchemy_fast ] && src+=(--kernel-source ssao_alchemy_fast.glsl=.old/alchemy_fast_B.glsl) ;;
      esac
      d=$work/$v.$k.r$r
      timeout 120 .bundle/render.sh --matrix gpu --filter "^corner/$k/n16/b4/full/1920x1080/(gl|vk)/compute\$" --max-noise 0.5 --max-time 1 "${src[@]}" --out $d > $d.log 2>&1
      echo "$v $k r$r rc $? ($(( $(date +%s) - start )) s)"
      find $d -type f ! -name manifest.json -delete
    done
  done
done
smi_stop
tar -C $work -czf $OUT/ab3_call.tgz .
