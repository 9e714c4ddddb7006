#!/usr/bin/env bash
# AO-pass experiments, round 2 (H200): alchemy_fast as committed (closed-form
# source pixel, spiral table) against a deinterleaved dispatch, against the
# same without `precise` (the cost of CPU-exact maths), and OpenGL from GLSL
# text instead of SPIR-V. 1920x1080 n16 b4 full, compute, 3 interleaved rounds.
set -uo pipefail
cd "$(dirname "$0")/.."
. scripts/gpu_env.sh
work=/tmp/exp2; rm -rf $work; mkdir -p $work
E=lab/2026-12-02_h200_ao_experiments/variants
declare -A V
V[new]=""
V[deint]="--kernel-source ssao_alchemy_fast.glsl=$E/ao2_deint.glsl"
V[noprecise]="--kernel-source ssao_alchemy_fast.glsl=$E/ao2_noprecise.glsl --kernel-source include/common.glsl=$E/common_noprecise.glsl"
V[deint_noprecise]="--kernel-source ssao_alchemy_fast.glsl=$E/ao2_deint_noprecise.glsl --kernel-source include/common.glsl=$E/common_noprecise.glsl"
smi_start $work/clocks.csv
F='^corner/(alchemy|alchemy_fast|hemisphere)/n16/b4/full/1920x1080/(gl|vk)/compute$'
for round in 1 2 3; do
  for v in new deint noprecise deint_noprecise; do
    d=$work/$v.r$round
    timeout 120 .bundle/render.sh --matrix gpu --filter '^corner/alchemy_fast/n16/b4/full/1920x1080/(gl|vk)/compute$' \
      --max-noise 0.5 --max-time 1 ${V[$v]} --out $d > $d.log 2>&1
    echo "$v r$round rc $? $(tail -1 $d.log)"
    find $d -type f ! -name manifest.json -delete
  done
  for glsl in 0 1; do
    d=$work/glsl$glsl.r$round
    if [ $glsl = 1 ]; then export CAVITY_GL_FORCE_GLSL=1; else unset CAVITY_GL_FORCE_GLSL; fi
    timeout 120 .bundle/render.sh --matrix gpu --backend gl --filter "$F" --max-noise 0.5 --max-time 1 --out $d > $d.log 2>&1
    echo "glsl$glsl r$round rc $? $(tail -1 $d.log)"
    find $d -type f ! -name manifest.json -delete
  done
  unset CAVITY_GL_FORCE_GLSL
done
smi_stop
tar -C $work -czf $OUT/exp2.tgz .
