#!/usr/bin/env bash
# Runs on the GPU machine (through the device tool), from the repo root, with
# .gl and .bundle carried: unpacks the GL/Vulkan loaders, records the clocks,
# runs the full benchmark sweep, and leaves everything in $OUT.
#   scripts/gpu_sweep.sh [extra cavity_bench flags]
set -uo pipefail
for f in .gl/*.deb; do dpkg -x "$f" /; done
ldconfig
if ! ls /usr/share/vulkan/icd.d/*nvidia* >/dev/null 2>&1 && ! ls /etc/vulkan/icd.d/*nvidia* >/dev/null 2>&1; then
  export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
fi
if ! ls /usr/share/glvnd/egl_vendor.d/*nvidia* >/dev/null 2>&1; then
  export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
fi
out="${OUT:-/tmp/out}"
mkdir -p "$out"
q='--query-gpu=name,driver_version,clocks.sm,clocks.mem,clocks.max.sm,power.draw,temperature.gpu'
nvidia-smi "$q" --format=csv > "$out/clocks_before.csv" 2>&1
export CAVITY_GPU_CLOCKS="$(tail -1 "$out/clocks_before.csv")"
.bundle/run.sh --sweep gpu --benchmark_out="$out/gpu_sweep.json" --benchmark_out_format=json "$@" \
  > "$out/gpu_sweep.txt" 2> "$out/gpu_sweep.err"
rc=$?
nvidia-smi "$q" --format=csv > "$out/clocks_after.csv" 2>&1
tail -5 "$out/gpu_sweep.txt"; tail -5 "$out/gpu_sweep.err"
exit $rc
