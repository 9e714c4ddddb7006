#!/usr/bin/env bash
# GL against Vulkan on alchemy_fast's passes reduced to their stores (and a
# copy): is GL's extra time in the work, or in every store or dispatch?
# Run from the repository root on the GPU machine, .gl and .bundle carried.
set -uo pipefail
cd "$(dirname "$0")/../.."
. scripts/gpu_env.sh
v=lab/2026-12-02_h200_gl_gap/variants
work=/tmp/exp4; rm -rf $work; mkdir -p $work
declare -A V
V[base]=""
V[bx_copy]="--kernel-source blur_separable_x.glsl=$v/bx_copy.glsl"
V[bx_store]="--kernel-source blur_separable_x.glsl=$v/bx_store.glsl"
V[stores]="--kernel-source composite.glsl=$v/comp_store.glsl --kernel-source ssao_alchemy_fast.glsl=$v/ao_store.glsl"
smi_start $work/clocks.csv
for round in 1 2 3; do
  for k in base bx_copy bx_store stores; do
    d=$work/$k.r$round
    timeout 120 .bundle/render.sh --matrix gpu --filter '^corner/alchemy_fast/n16/b4/full/1920x1080/(gl|vk)/compute$' \
      --max-noise 0.5 --max-time 1 ${V[$k]} --out $d > $d.log 2>&1
    echo "$k r$round rc $? $(tail -1 $d.log)"
    find $d -type f ! -name manifest.json -delete
  done
done
smi_stop
tar -C $work -czf $OUT/exp4.tgz .
