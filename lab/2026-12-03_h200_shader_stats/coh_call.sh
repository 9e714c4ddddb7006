#!/usr/bin/env bash
# One phase for every pixel (coh) against the committed per-pixel hash, each
# with plain and interleave=4 dispatch (the coh matrix), ROUNDS shuffled
# rounds, each variant and kernel its own cavity_render process, on the H200.
#   .old/coh_call.sh ROUNDS       (carry .gl .bundle .old)
set -uo pipefail
cd "$(dirname "$0")/.."
. scripts/gpu_env.sh
for f in .bundle/*.xz; do xz -dk "$f"; done; chmod +x .bundle/cavity_bench .bundle/cavity_render
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
work=$(mktemp -d)
smi_start $work/clocks.csv
for r in $(seq 1 "$1"); do
  for v in $(printf 'new\ncoh\n' | shuf); do
    for k in alchemy_fast hemisphere_fast; do
      src=(); [ $v = coh ] && src=(--kernel-source ssao_$k.glsl=.old/coh/ssao_$k.glsl)
      d=$work/$v.$k.r$r
      timeout 120 .bundle/render.sh --matrix coh --baselines .old/base --filter "^corner/$k/" --max-noise 0.5 --max-time 1 "${src[@]}" --out $d > $d.log 2>&1
      echo "$v $k r$r rc $? ($(el) s)"
      find $d -type f ! -name manifest.json -delete
    done
  done
done
smi_stop
tar -C $work -czf $OUT/coh_call.tgz .
