#!/usr/bin/env bash
# AO-pass experiments on the H200: alchemy_fast's AO pass and the separable
# blur with kernel sources swapped at run time (cavity_render --kernel-source),
# 1920x1080 n16 b4 full, compute, both APIs, 3 interleaved rounds.
set -uo pipefail
cd "$(dirname "$0")/.."
. scripts/gpu_env.sh
work=/tmp/exp; rm -rf $work; mkdir -p $work
E=lab/2026-12-02_h200_ao_experiments/variants
declare -A V
V[v0]=""
V[closed]="--kernel-source ssao_alchemy_fast.glsl=$E/ao_closed.glsl"
V[cheap]="--kernel-source ssao_alchemy_fast.glsl=$E/ao_closed.glsl --kernel-source include/alchemy_spiral.glsl=$E/spiral_cheap.glsl"
V[const_u]="--kernel-source ssao_alchemy_fast.glsl=$E/ao_const_u.glsl"
V[tile_u]="--kernel-source ssao_alchemy_fast.glsl=$E/ao_tile_u.glsl"
V[deint]="--kernel-source ssao_alchemy_fast.glsl=$E/ao_deint.glsl"
V[deint_closed]="--kernel-source ssao_alchemy_fast.glsl=$E/ao_deint_closed.glsl"
V[deint_cheap]="--kernel-source ssao_alchemy_fast.glsl=$E/ao_deint_closed.glsl --kernel-source include/alchemy_spiral.glsl=$E/spiral_cheap.glsl"
V[blur_tiled]="--kernel-source blur_separable_x.glsl=$E/blur_sep_x.glsl --kernel-source blur_separable_y.glsl=$E/blur_sep_y.glsl"
V[all]="${V[deint_closed]} ${V[blur_tiled]}"
smi_start $work/clocks.csv
for round in 1 2 3; do
  for v in v0 closed cheap const_u tile_u deint deint_closed deint_cheap blur_tiled all; do
    d=$work/$v.r$round
    timeout 120 .bundle/render.sh --matrix gpu --filter '^corner/alchemy_fast/n16/b4/full/1920x1080/(gl|vk)/compute$' \
      --max-noise 0.5 --max-time 1 ${V[$v]} --out $d > $d.log 2>&1
    echo "$v r$round rc $? $(tail -1 $d.log)"
    find $d -type f ! -name manifest.json -delete
  done
done
smi_stop
nvidia-smi -q > $work/nvidia-smi.txt 2>&1
tar -C $work -czf $OUT/exp.tgz .
