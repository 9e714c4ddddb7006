#!/usr/bin/env bash
# What a pass time stands on, and half floats in the AO pass, on the GPU
# machine in one call (docs/timing.md, "GL's gap on the H200";
# docs/kernels.md, "The precision contract"):
#  1. the overhead probes (bench/overhead_probes.h: a timestamp pair alone,
#     an empty 1920x1080 dispatch, a store-only one, in chains of 8 passes
#     with no pass reading another), with the barriers as they are, the
#     widest (CAVITY_FULL_BARRIERS=1) and none (CAVITY_NO_BARRIERS=1);
#  2. alchemy_fast n16 b4 full and half, both APIs, with the barriers as
#     they are and none (the pipeline's images are then undefined; only the
#     time is read);
#  3. tiles (CAVITY_TILE, an experiment since reverted: apply
#     lab/2026-12-03_h200_overheads/variants/tile.patch before
#     building the bundle, else the three settings are one): alchemy_fast n16 b4 full, half
#     and half with the fused tail, both APIs, with each kernel's own tile
#     (2x2 in the upsamples), one pixel an invocation everywhere (1x1, as
#     before) and 2x2 wherever a kernel may; then the half-resolution
#     renders' digests with the kernels' own tiles and with 1x1, which must
#     be the same;
#  4. alchemy_fast with its per-sample arithmetic in half floats against
#     the same kernel in floats, both --exact 0
#     (lab/2026-12-03_h200_overheads/variants/), timed by
#     cavity_render, then its quality against the ground truth after the
#     blur, corner and slats, n16 and n32.
# Each step's variants run as separate processes in a shuffled order,
# ROUNDS rounds, the clocks sampled beside them. Leaves overheads.tgz in $OUT.
# As run. The variants it reads as NAME.glsl are kept as diffs against
# c096d07 (lab/2026-12-03_h200_overheads/README.md says how to
# rebuild them there first).
#   lab/scripts/gpu_overheads.sh [ROUNDS (3)] [MAX_TIME_S (0.3)] [STEPS ("probes chain tile fp16 quality")]
set -uo pipefail
cd "$(dirname "$0")/.."
. scripts/gpu_env.sh
rounds="${1:-3}"
maxt="${2:-0.3}"
steps=" ${3:-probes chain tile fp16 quality} "
want() { [[ "$steps" == *" $1 "* ]]; }
work=$(mktemp -d)
V=lab/2026-12-03_h200_overheads/variants
start=$(date +%s)
env_of() { case $1 in full) echo CAVITY_FULL_BARRIERS=1 ;; none) echo CAVITY_NO_BARRIERS=1 ;; *) echo CAVITY_X=0 ;; esac; }
smi_start "$work/clocks.csv"
for r in $(seq 1 "$rounds"); do
  want probes && for b in $(printf 'narrow\nfull\nnone\n' | shuf); do
    env "$(env_of "$b")" timeout 120 .bundle/run.sh --sweep gpu --benchmark_filter='^timer/' \
      --benchmark_out="$work/probes_$b.r$r.json" --benchmark_out_format=json > "$work/probes_$b.r$r.txt" 2>&1
    echo "probes $b r$r: rc $? ($(( $(date +%s) - start )) s)"
  done
  want chain && for b in $(printf 'narrow\nnone\n' | shuf); do
    env "$(env_of "$b")" timeout 150 .bundle/run.sh --sweep gpu \
      --benchmark_filter='^corner/alchemy_fast/n16/b4/(full|half)/1920x1080/(gl|vk)/compute/' \
      --benchmark_repetitions=3 --benchmark_enable_random_interleaving=true --max-time "$maxt" \
      --benchmark_out="$work/chain_$b.r$r.json" --benchmark_out_format=json > "$work/chain_$b.r$r.txt" 2>&1
    echo "chain $b r$r: rc $? ($(( $(date +%s) - start )) s)"
  done
  want tile && for t in $(printf 'own\n1x1\n2x2\n' | shuf); do
    CAVITY_TILE=$([ $t = own ] || echo $t) timeout 150 .bundle/run.sh --sweep gpu \
      --benchmark_filter='^corner/alchemy_fast/n16/b4/((fused_tail=1)/)?(full|half)/1920x1080/(gl|vk)/compute/' \
      --benchmark_repetitions=3 --benchmark_enable_random_interleaving=true --max-time "$maxt" \
      --benchmark_out="$work/tile_$t.r$r.json" --benchmark_out_format=json > "$work/tile_$t.r$r.txt" 2>&1
    echo "tile $t r$r: rc $? ($(( $(date +%s) - start )) s)"
  done
  want fp16 && for v in $(printf 'inexact\nfp16\n' | shuf); do
    d="$work/render_$v.r$r"
    timeout 150 .bundle/render.sh --matrix gpu --filter '^corner/alchemy_fast/n16/b4/full/1920x1080/(gl|vk)/compute$' \
      --max-noise 0.5 --max-time 1 --kernel-source "ssao_alchemy_fast.glsl=$V/alchemy_fast_$v.glsl" --out "$d" > "$d.log" 2>&1
    echo "render $v r$r: rc $? ($(( $(date +%s) - start )) s) $(tail -1 "$d.log")"
    find "$d" -type f ! -name manifest.json -delete
  done
done
smi_stop
want tile && for t in own 1x1; do
  CAVITY_TILE=$([ $t = own ] || echo $t) timeout 150 .bundle/render.sh --matrix gpu \
    --filter '^corner/(alchemy|alchemy_fast)/n16/b4/half/1920x1080/(gl|vk)/(compute|fragment)$' --out "$work/digests_$t" \
    > "$work/digests_$t.log" 2>&1
  echo "digests $t: rc $? $(tail -1 "$work/digests_$t.log")"
  find "$work/digests_$t" -type f ! -name manifest.json -delete
done
want tile && python3 - "$work" <<'PY'
import json, sys
def digests(d):
    m = json.load(open(f"{sys.argv[1]}/digests_{d}/manifest.json"))
    return {(c["id"], i["name"]): i["digest"] for c in m["configurations"] for r in c["renders"] for i in r["images"]}
own, single = digests("own"), digests("1x1")
same = sum(own[k] == single.get(k) for k in own)
print(f"tile digests: {same} of {len(own)} images the same with the kernels' own tiles and with 1x1")
for k in own:
    if own[k] != single.get(k): print("  differs:", k)
PY
# Quality: the float kernel with --exact 0, and the half-float one.
want quality && for v in inexact fp16; do
  src=(); [ $v = fp16 ] && src=(--kernel-source "ssao_alchemy_fast.glsl=$V/alchemy_fast_fp16.glsl")
  for s in corner slats; do
    timeout 200 .bundle/render.sh quality --backend vk --res 1920x1080 --scene "$s" --kernel alchemy_fast --samples 16,32 \
      --reach shared --blur 4 --exact 0 "${src[@]}" --quiet --out "$work/quality_${v}_$s" > "$work/quality_${v}_$s.txt" 2>&1
    echo "quality $v $s: rc $? ($(( $(date +%s) - start )) s)"
    cat "$work/quality_${v}_$s.txt"
  done
done
tar -C "$work" -czf "$OUT/overheads_$(echo $steps | tr " " _).tgz" .
ls -la "$OUT"
