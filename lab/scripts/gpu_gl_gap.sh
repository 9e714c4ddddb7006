#!/usr/bin/env bash
# Is the per-pass gap between cavity_render's and cavity_bench's OpenGL
# times (about 20 us against 3 us a pass on the H200) the one chain
# cavity_render measures, where cavity_bench turns four camera views
# (docs/timing.md, "One chain or several views")? On the GPU machine, in one
# call: ROUNDS rounds, each cavity_render of alchemy_fast at 1920x1080 on both
# APIs with --views 1 and --views 4, and cavity_bench of the same
# configuration, and with --views 4 the composite reduced to its store
# (store4) and to an empty dispatch (empty4, lab/scripts/gl_gap/), which part
# of GL's per-pass cost is the pass itself; the five in a shuffled order,
# the clocks beside them.
# Leaves gl_gap.tgz (the render manifests, the benchmark JSON) in $OUT.
#   lab/scripts/gpu_gl_gap.sh [ROUNDS (3)]
set -uo pipefail
cd "$(dirname "$0")/.."
. scripts/gpu_env.sh
rounds="${1:-3}"
id='corner/alchemy_fast/n16/b4/full/1920x1080/(gl|vk)/compute'
work=$(mktemp -d)
smi_start "$work/clocks.csv"
for r in $(seq 1 "$rounds"); do
  for k in $(printf 'views1\nviews4\nbench\nstore4\nempty4\n' | shuf); do
    d="$work/$k.r$r"
    case $k in
      views1|views4|store4|empty4)
        src=()
        case $k in
          store4) src=(--kernel-source composite.glsl=lab/scripts/gl_gap/composite_store.glsl) ;;
          empty4) src=(--kernel-source composite.glsl=lab/scripts/gl_gap/composite_empty.glsl) ;;
        esac
        timeout 180 .bundle/render.sh --matrix gpu --filter "^$id\$" --max-noise 0.5 --max-time 1 \
          --views "${k: -1}" "${src[@]}" --out "$d" > "$d.log" 2>&1
        echo "$k r$r: rc $? $(tail -1 "$d.log")"
        find "$d" -type f ! -name manifest.json -delete ;;
      bench)
        timeout 180 .bundle/run.sh --sweep gpu --benchmark_filter="^$id/" --benchmark_repetitions=3 \
          --max-time 1 --benchmark_out="$d.json" --benchmark_out_format=json > "$d.log" 2>&1
        echo "$k r$r: rc $?" ;;
    esac
  done
done
smi_stop
tar -C "$work" -czf "$OUT/gl_gap.tgz" .
ls -la "$OUT"
