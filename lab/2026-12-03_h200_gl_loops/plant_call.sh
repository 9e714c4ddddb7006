#!/usr/bin/env bash
# 512 planted FMAs in alchemy_fast's AO pass, after its loop (the images are
# unchanged: the result is multiplied by frame.pad_, 0): a dependent chain in
# a loop (loop), the same chain written out (straight), four independent
# chains of 128 in a loop (vec4), against the kernel as it is (base); ROUNDS
# shuffled rounds, each variant its own cavity_render process, both APIs.
set -uo pipefail
cd "$(dirname "$0")/.."
for f in .bundle/*.xz; do xz -dk "$f"; done; chmod +x .bundle/cavity_render
. scripts/gpu_env.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
work=$(mktemp -d)
smi_start $work/clocks.csv
for r in $(seq 1 "$1"); do
  for v in $(printf 'base\nloop\nstraight\nvec4\n' | shuf); do
    src=(); [ $v != base ] && src=(--kernel-source ssao_alchemy_fast.glsl=.old/plant/$v.glsl)
    d=$work/$v.r$r
    timeout 120 .bundle/render.sh --matrix ab --baselines .old/base --filter '^corner/alchemy_fast/n16/b4/full/1920x1080/(gl|vk)/compute$' \
      --max-noise 0.5 --max-time 1 "${src[@]}" --out $d > $d.log 2>&1
    echo "$v r$r rc $? ($(el) s)"
    find $d -type f ! -name manifest.json -delete
  done
  tar -C $work -czf $OUT/plant_call.tgz .   # after every round: a cut call still brings back the rounds done
done
smi_stop
tar -C $work -czf $OUT/plant_call.tgz .
