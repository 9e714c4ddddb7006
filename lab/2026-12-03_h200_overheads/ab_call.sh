#!/usr/bin/env bash
# The fifth call: the fast kernels as in the tree ("new", the pyramidTexel
# form) against 914f511's (= c096d07's) include/pyramid.glsl and
# ssao_alchemy_fast.glsl ("old"), corner n16 b4 full and half 1920x1080
# compute, both APIs, each its own cavity_render process, ROUNDS shuffled
# rounds. As run, from a tree where .old/ held the old sources:
#   mkdir .old; git show 914f511:kernels/include/pyramid.glsl > .old/pyramid.glsl
#   git show 914f511:kernels/ssao_alchemy_fast.glsl > .old/alchemy_fast.glsl
#   lab/2026-12-03_h200_overheads/ab_call.sh [ROUNDS]   (carry .old)
set -uo pipefail
cd "$(dirname "$0")/../.."
. scripts/gpu_env.sh
work=$(mktemp -d); start=$(date +%s)
smi_start "$work/clocks.csv"
for r in $(seq 1 "$1"); do
  for v in $(printf 'new\nold\n' | shuf); do
    for k in alchemy_fast hemisphere_fast; do
      src=(); [ $v = old ] && src=(--kernel-source include/pyramid.glsl=.old/pyramid.glsl --kernel-source ssao_alchemy_fast.glsl=.old/alchemy_fast.glsl)
      [ $v = old ] && [ $k = hemisphere_fast ] && src=(--kernel-source include/pyramid.glsl=.old/pyramid.glsl)
      d=$work/$v.$k.r$r
      timeout 120 .bundle/render.sh --matrix gpu --filter "^corner/$k/n16/b4/(full|half)/1920x1080/(gl|vk)/compute\$" --max-noise 0.5 --max-time 1 "${src[@]}" --out $d > $d.log 2>&1
      echo "$v $k r$r rc $? ($(( $(date +%s) - start )) s)"
      find $d -type f ! -name manifest.json -delete
    done
  done
done
smi_stop
tar -C $work -czf $OUT/ab_call.tgz .
