# Sourced by the scripts that run on the GPU machine (docs/gpu.md),
# from the repository root with .gl and .bundle carried: unpacks the GL and
# Vulkan loaders, points them at the NVIDIA driver where the image does not,
# and sets OUT (the folder that comes back).
# Only there: on a machine without the NVIDIA driver (a dry run of a
# script on a CPU renderer) the system's own loaders stay as they are.
if command -v nvidia-smi >/dev/null 2>&1; then
  for f in .gl/*.deb; do dpkg -x "$f" /; done
  ldconfig
  if ! ls /usr/share/vulkan/icd.d/*nvidia* >/dev/null 2>&1 && ! ls /etc/vulkan/icd.d/*nvidia* >/dev/null 2>&1; then
    export VK_DRIVER_FILES=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
  fi
  if ! ls /usr/share/glvnd/egl_vendor.d/*nvidia* >/dev/null 2>&1; then
    export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
  fi
fi
# The bundle's binaries travel xz-compressed (scripts/bundle.sh).
[ -x .bundle/unpack.sh ] && .bundle/unpack.sh
OUT="${OUT:-/tmp/out}"
mkdir -p "$OUT"
export OUT
# Never change the clocks; record them. One row per nvidia-smi interval (-lms) while $1 runs:
#   smi_start FILE; ...; smi_stop
smi_start() {
  command -v nvidia-smi >/dev/null 2>&1 || { echo "no nvidia-smi here" > "$1"; SMI_PID=; return 0; }
  nvidia-smi --query-gpu=timestamp,clocks.sm,clocks.mem,power.draw,temperature.gpu,clocks_event_reasons.active \
    --format=csv -lms 200 > "$1" 2>&1 &
  SMI_PID=$!
}
smi_stop() { [ -n "${SMI_PID:-}" ] && kill "$SMI_PID" 2>/dev/null; wait "$SMI_PID" 2>/dev/null; SMI_PID=; }
# One cavity_bench run of the gpu sweep, its configurations' repetitions
# interleaved, with the clocks sampled beside it: $OUT/NAME.json, .txt, .err
# and .clocks.csv. The caller sets filter, reps and maxt (and start, for the
# elapsed seconds it prints); the flags given may not repeat these (cavity_bench
# refuses a flag given twice).
#   bench NAME [more cavity_bench flags...]
bench() {
  local name=$1; shift
  echo "== $name ($(( $(date +%s) - ${start:-$(date +%s)} )) s)"
  smi_start "$OUT/$name.clocks.csv"
  .bundle/run.sh --sweep gpu --benchmark_filter="$filter" --benchmark_repetitions="$reps" \
    --benchmark_enable_random_interleaving=true --max-time "$maxt" \
    --benchmark_out="$OUT/$name.json" --benchmark_out_format=json "$@" > "$OUT/$name.txt" 2> "$OUT/$name.err"
  local rc=$?
  smi_stop
  tail -1 "$OUT/$name.err"
  return $rc
}
