#!/usr/bin/env bash
# References of a GPU, made on the GPU machine (through the device tool, .gl
# and .bundle carried; docs/gpu.md): renders a matrix once, approves its
# digests for the device's class (cavity baselines approve, from the render
# folder: no image travels), then renders it again and again and judges each
# render there, by digest. What comes back in $OUT is small: approvals.json,
# each clean run's gate.json and summary.md, the manifests, the clocks.
#   scripts/gpu_references.sh MATRIX SECONDS [FILTER]
# renders until SECONDS have passed (at least one clean render); FILTER, a
# regular expression, keeps the configurations whose id it matches (those of
# the kernels an edit touched), as cavity_render --filter does.
# Back here: copy $OUT/approvals.json to baselines/ after review.
set -uo pipefail
cd "$(dirname "$0")/.."
. scripts/gpu_env.sh
matrix="${1:-gpu}"; budget="${2:-300}"; filter="${3:-}"
only=(); [ -n "$filter" ] && only=(--filter "$filter")
work=/tmp/cavity-references
rm -rf "$work"; mkdir -p "$work" "$OUT"
cp -r baselines "$work/base"
smi_start "$OUT/clocks.csv"
start=$(date +%s)
ms() { echo $(( ($(date +%s%N) - $1) / 1000000 )); }
t0=$(date +%s%N)
.bundle/render.sh --matrix "$matrix" "${only[@]}" --baselines "$work/base" --out "$work/r0" 2> "$OUT/render0.err"
echo "render 0: exit $? in $(ms "$t0") ms" | tee -a "$OUT/log.txt"
cp "$work/r0/manifest.json" "$OUT/manifest0.json"
.bundle/cavity.sh baselines approve --from "$work/r0" --baselines "$work/base" --by gpu_references.sh \
  --why "$matrix${filter:+ (configurations matching $filter)} rendered on $(nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | head -1)" | tee -a "$OUT/log.txt"
cp "$work/base/approvals.json" "$OUT/approvals.json"
i=1
while [ "$i" -eq 1 ] || [ $(( $(date +%s) - start )) -lt "$budget" ]; do
  t0=$(date +%s%N)
  .bundle/render.sh --matrix "$matrix" "${only[@]}" --baselines "$work/base" --out "$work/r$i" 2> "$OUT/render$i.err"
  rc=$?
  t1=$(date +%s%N)
  .bundle/cavity.sh gate judge "$work/r$i" --baselines "$work/base" --out "$work/g$i" --quiet > "$OUT/summary$i.md"
  jrc=$?
  t2=$(date +%s%N)
  echo "clean render $i: render exit $rc in $(( (t1 - t0) / 1000000 )) ms, manifest $(stat -c %s "$work/r$i/manifest.json") bytes, image files $(find "$work/r$i" -name '*.f32z' | wc -l); judge exit $jrc in $(( (t2 - t1) / 1000000 )) ms" | tee -a "$OUT/log.txt"
  cp "$work/g$i/gate.json" "$OUT/gate$i.json"
  i=$((i + 1))
done
smi_stop
du -sh "$OUT" | tee -a "$OUT/log.txt"
