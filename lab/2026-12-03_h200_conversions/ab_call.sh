#!/usr/bin/env bash
# Conversion-free sample loops against the committed sources (old) and a
# variant that also floors without a conversion in exact mode (v2), on the
# H200: first the gpu matrix's fast kernels (digests against the approvals),
# then ROUNDS shuffled rounds, each variant and kernel its own cavity_render
# process over the ab matrix (corner n16 b4 full 1920x1080 compute, exact
# and exact=0, gl and vk), then quality of the new exact=0 kernels.
#   .old/ab_call.sh ROUNDS MAX_S      (carry .gl .bundle .old)
# As run (5 360), from a tree with no_conversions.patch applied and bundled
# (BUNDLE_BINARIES="cavity_bench cavity_render"), where .old/ held the
# committed sources of kernels/include/common.glsl, include/pyramid.glsl,
# ssao_alchemy_fast.glsl and ssao_hemisphere_fast.glsl (old), the files of
# v2_on_top.patch in .old/v2/, and in .old/base/matrices.json the repository's
# matrices plus "ab": corner, alchemy_fast and hemisphere_fast, n16, b4,
# params {"exact": [1, 0]}, full, 1920x1080, gl and vk, compute.
set -uo pipefail
cd "$(dirname "$0")/.."
. scripts/gpu_env.sh
work=$(mktemp -d); start=$(date +%s)
el() { echo $(( $(date +%s) - start )); }
timeout 240 .bundle/render.sh --matrix gpu --filter '^corner/(alchemy|hemisphere|ssdo)_fast/' --out $work/digests > $work/digests.log 2>&1
echo "digests rc $? ($(el) s)"
find $work/digests -type f ! -name manifest.json -delete
smi_start $work/clocks.csv
for r in $(seq 1 "$1"); do
  [ "$(el)" -gt "$2" ] && break
  for v in $(printf 'new\nold\nv2\n' | shuf); do
    for k in alchemy_fast hemisphere_fast; do
      case $v in
        new) src=() ;;
        old) src=(--kernel-source include/common.glsl=.old/common.glsl --kernel-source include/pyramid.glsl=.old/pyramid.glsl
                  --kernel-source ssao_$k.glsl=.old/ssao_$k.glsl) ;;
        v2) src=(--kernel-source include/common.glsl=.old/v2/common.glsl --kernel-source include/pyramid.glsl=.old/v2/pyramid.glsl)
            [ $k = alchemy_fast ] && src+=(--kernel-source ssao_alchemy_fast.glsl=.old/v2/ssao_alchemy_fast.glsl) ;;
      esac
      d=$work/$v.$k.r$r
      timeout 120 .bundle/render.sh --matrix ab --baselines .old/base --filter "^corner/$k/" --max-noise 0.5 --max-time 1 "${src[@]}" --out $d > $d.log 2>&1
      echo "$v $k r$r rc $? ($(el) s)"
      find $d -type f ! -name manifest.json -delete
    done
  done
done
smi_stop
for s in corner slats; do
  timeout 150 .bundle/render.sh quality --backend vk --res 1920x1080 --scene $s --kernel alchemy_fast,hemisphere_fast \
    --samples 16,32 --reach shared --blur 4 --exact 0 --out $work/quality_$s > $work/quality_$s.txt 2>&1
  echo "quality $s rc $? ($(el) s): $(tail -1 $work/quality_$s.txt)"
done
tar -C $work -czf $OUT/ab_call.tgz .
