#!/usr/bin/env bash
# Runs on the GPU machine (through the device tool), from the repo root, with
# .gl and .bundle carried: unpacks the GL/Vulkan loaders, records the clocks,
# renders a gate matrix with cavity_render and packs the render folder into
# $OUT as render.tar.00, .01, ... (the device tool returns at most 8 files of
# 16 MiB, 64 MiB in all, two folders deep).
#   scripts/gpu_render.sh --matrix gpu [other cavity_render flags, not --out]
# Back here: cat render.tar.* | tar -x -C out/ && build/harness/cavity gate judge out/render --out out/gate
set -uo pipefail
cd "$(dirname "$0")/.."
. scripts/gpu_env.sh
out="${OUT:-/tmp/out}"
work=/tmp/cavity-render
rm -rf "$work"
mkdir -p "$out" "$work"
q='--query-gpu=name,driver_version,clocks.sm,clocks.mem,clocks.max.sm,power.draw,temperature.gpu'
nvidia-smi "$q" --format=csv > "$work/clocks_before.csv" 2>&1
.bundle/render.sh "$@" --out "$work/render" 2> "$work/render.err"
rc=$?
nvidia-smi "$q" --format=csv > "$work/clocks_after.csv" 2>&1
cp "$work"/clocks_*.csv "$work/render.err" "$work/render/" 2>/dev/null
tail -3 "$work/render.err"
# The images are zlib already: tar, no compression, in parts under 16 MiB.
tar -C "$work" -cf - render | split -b 15M -d - "$out/render.tar."
parts=$(ls "$out"/render.tar.* | wc -l)
mib=$(du -cm "$out"/render.tar.* | tail -1 | cut -f1)
echo "gpu_render: $parts parts, $mib MiB in $out"
if [ "$parts" -gt 8 ] || [ "$mib" -gt 63 ]; then
  echo "gpu_render: over what comes back (8 files, 64 MiB): render in shards (--shard I/N), one call each" >&2
  exit 1
fi
exit $rc
