#!/usr/bin/env bash
# The fast AO kernels' per-sample integer work made leaner, the same bits:
# alchemy_fast with its own leaner loop (variants/alchemy_fast_lean.glsl:
# an unsigned bounds test, the tiny-level branch and levelSize's max()
# decided once per pixel), and both kernels with the shared helpers'
# tiny-level test from the frame's size alone and an unsigned bounds test
# (variants/pyramid_lean.glsl), against the kernels as committed; and, as
# a probe of cost only (wrong images), alchemy_fast rebuilding samples on
# the texel's corner pixel, without undoing the pyramid's picks
# (variants/alchemy_fast_nosource.glsl): corner
# n16 b4 full 1920x1080 compute, both APIs, each variant its own
# cavity_render process, ROUNDS shuffled rounds, the clocks beside them.
# Leaves lean.tgz in $OUT.
# As run. The variants it reads as NAME.glsl are kept as diffs against
# c096d07 (lab/2026-12-03_h200_overheads/README.md says how to
# rebuild them there first).
#   lab/2026-12-03_h200_overheads/lean_rounds.sh [ROUNDS (3)]
set -uo pipefail
cd "$(dirname "$0")/../.."
. scripts/gpu_env.sh
rounds="${1:-3}"
work=$(mktemp -d)
V=lab/2026-12-03_h200_overheads/variants
declare -A SRC KERNEL
SRC[a_committed]="";                                                    KERNEL[a_committed]=alchemy_fast
SRC[a_lean]="--kernel-source ssao_alchemy_fast.glsl=$V/alchemy_fast_lean.glsl"; KERNEL[a_lean]=alchemy_fast
SRC[a_nosource]="--kernel-source ssao_alchemy_fast.glsl=$V/alchemy_fast_nosource.glsl"; KERNEL[a_nosource]=alchemy_fast
SRC[a_pyr]="--kernel-source include/pyramid.glsl=$V/pyramid_lean.glsl";  KERNEL[a_pyr]=alchemy_fast
SRC[h_committed]="";                                                    KERNEL[h_committed]=hemisphere_fast
SRC[h_pyr]="--kernel-source include/pyramid.glsl=$V/pyramid_lean.glsl";  KERNEL[h_pyr]=hemisphere_fast
start=$(date +%s)
smi_start "$work/clocks.csv"
for r in $(seq 1 "$rounds"); do
  for v in $(printf '%s\n' "${!SRC[@]}" | shuf); do
    d="$work/$v.r$r"
    timeout 120 .bundle/render.sh --matrix gpu --filter "^corner/${KERNEL[$v]}/n16/b4/full/1920x1080/(gl|vk)/compute\$" \
      --max-noise 0.5 --max-time 1 ${SRC[$v]} --out "$d" > "$d.log" 2>&1
    echo "$v r$r: rc $? ($(( $(date +%s) - start )) s)"
    find "$d" -type f ! -name manifest.json -delete
  done
done
smi_stop
tar -C "$work" -czf "$OUT/lean.tgz" .
