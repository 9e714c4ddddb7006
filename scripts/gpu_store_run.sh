#!/usr/bin/env bash
# One API's references of a GPU into an image store, and planted defects
# judged against them, on the GPU machine (through the device tool, .gl and
# .bundle carried; docs/gpu.md, docs/store.md):
#   1. renders MATRIX on API with every image written (no approvals given),
#   2. approves it with `cavity baselines approve --store` as a user would:
#      every image goes into a folder store, the digests into approvals.json,
#   3. renders each planted defect of DEFECTS_DIR (scripts/planted_defects.sh)
#      with `cavity_render --store`, judged there against those references;
#      only the manifests (verdicts and metrics) come back,
#   4. renders MATRIX once more with --store and judges it there (CLEAN=1).
# $OUT gets a log and results.tgz: the approvals, the planted defects'
# manifests, the store's index (digest, bytes, sha256 of each object; the
# store itself, about 90 MiB an API at 1920x1080, stays there), the clocks.
#   scripts/gpu_store_run.sh MATRIX API DEFECTS_DIR
# FILTER (a regular expression) keeps MATRIX's configurations whose id it
# matches, and a defect's configurations that it matches too.
set -uo pipefail
cd "$(dirname "$0")/.."
. scripts/gpu_env.sh
matrix="$1"; api="$2"; defects="$3"
filter="${FILTER:-}"
only=(); [ -n "$filter" ] && only=(--filter "$filter")
work=/tmp/cavity-store-run
rm -rf "$work"; mkdir -p "$work" "$OUT/planted"
cp -r .bundle/baselines "$work/base"
mkdir -p "$work/none"; cp .bundle/baselines/*.json "$work/none/"; rm -f "$work/none/approvals.json"
gpu="$(nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | head -1)"
smi_start "$OUT/clocks.csv"
ms() { echo $(( ($(date +%s%N) - $1) / 1000000 )); }
log() { echo "$*" | tee -a "$OUT/log.txt"; }
t0=$(date +%s%N)
.bundle/render.sh --matrix "$matrix" "${only[@]}" --backend "$api" --baselines "$work/none" --out "$work/r0" 2> "$OUT/render0.err"
log "render with every image: exit $? in $(ms "$t0") ms, $(du -sm "$work/r0" | cut -f1) MiB"
t0=$(date +%s%N)
.bundle/cavity.sh baselines approve --from "$work/r0" --baselines "$work/base" --store "$work/store" \
  --by gpu_store_run.sh --why "$matrix $api rendered on $gpu" 2>&1 | tee -a "$OUT/log.txt"
log "approve: $(ms "$t0") ms; store $(find "$work/store" -name '*.f32z' | wc -l) objects, $(du -sm "$work/store" | cut -f1) MiB"
cp "$work/base/approvals.json" "$OUT/approvals.json"
mkdir -p "$OUT/r"
(cd "$work/store" && find . -name '*.f32z' -printf '%P %s\n' | sort | while read -r f b; do
  echo "$f $b $(sha256sum "$f" | cut -c1-64)"; done) > "$OUT/r/store_index.txt"
while read -r name file touches; do
  t0=$(date +%s%N)
  .bundle/render.sh --matrix "$matrix" --backend "$api" --baselines "$work/base" --store "$work/store" \
    --filter "${filter:+^(?=.*$filter).*}$touches" --kernel-source "$file=$defects/$name.glsl" --out "$work/p_$name" > "$work/p_$name.out" 2>&1
  rc=$?
  log "planted $name: exit $rc in $(ms "$t0") ms: $(grep '^judged here' "$work/p_$name.out")"
  cp "$work/p_$name/manifest.json" "$OUT/planted/$name.json" 2>/dev/null
  rm -rf "$work/p_$name"
done < "$defects/list.txt"
if [ "${CLEAN:-1}" = 1 ]; then
t0=$(date +%s%N)
.bundle/render.sh --matrix "$matrix" "${only[@]}" --backend "$api" --baselines "$work/base" --store "$work/store" --out "$work/clean" \
  > "$work/clean.out" 2>&1
rc=$?
t1=$(date +%s%N)
.bundle/cavity.sh gate judge "$work/clean" --baselines "$work/base" --store "$work/store" --out "$work/g" --quiet \
  > "$OUT/clean_summary.md" 2>&1
jrc=$?
log "clean render: exit $rc in $(( (t1 - t0) / 1000000 )) ms, manifest $(stat -c %s "$work/clean/manifest.json") bytes, $(find "$work/clean" -name '*.f32z' | wc -l) image files; judge exit $jrc in $(ms "$t1") ms"
cp "$work/g/gate.json" "$OUT/clean_gate.json" 2>/dev/null
fi
smi_stop
# The device tool brings back a few files: one archive of the small ones.
mv "$OUT/planted" "$OUT/approvals.json" "$OUT/clocks.csv" "$OUT/render0.err" "$OUT/r/" 2>/dev/null
mv "$OUT"/clean_* "$OUT/r/" 2>/dev/null
tar -C "$OUT" -czf "$OUT/results.tgz" r && rm -rf "$OUT/r"
du -sh "$OUT" | tee -a "$OUT/log.txt"
