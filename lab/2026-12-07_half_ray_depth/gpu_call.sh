#!/usr/bin/env bash
# One device call after the half-resolution depth moved onto each half
# texel's own ray (include/downsample.glsl, halfRayDepth):
# 1. cavity ab, the build before (.bundle-old, cavity_bench only) against
#    this one (.bundle), 4 rounds, the fast kernels' half pipelines at
#    1920x1080: the downsample pass does a little more arithmetic per texel.
# 2. The CPU matrices (ci, gpu-cpu) and the gpu matrix's half-resolution
#    configurations of the kernels that read the pyramid rendered here,
#    approved by digest for this card's class through a folder store, then
#    judged against those approvals; approvals.json comes back.
#   bash lab/2026-12-07_half_ray_depth/gpu_call.sh   (.gl, .bundle, .bundle-old carried)
set -uo pipefail
cd "$(dirname "$0")/../.."
. scripts/gpu_env.sh
[ -x .bundle-old/unpack.sh ] && .bundle-old/unpack.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv > "$OUT/gpu.csv" 2>&1
cat "$OUT/gpu.csv"
f='^corner/(alchemy_fast|hemisphere_fast)/n16/b4/(half|fused_tail=1/half)/1920x1080/(gl|vk)/compute/'
smi_start "$OUT/ab.clocks.csv"
.bundle/cavity.sh ab --a .bundle-old --b .bundle --rounds 4 --filter "$f" --bench-args='--sweep gpu --max-time 0.3' \
  --out /tmp/ab > "$OUT/ab.txt" 2>&1
echo "ab: rc $? ($(el) s)"; smi_stop
grep -E "downsample|pipeline|frame" "$OUT/ab.txt" | head -40
cp /tmp/ab/compare.json "$OUT/ab_compare.json" 2>/dev/null; gzip -f "$OUT/ab.clocks.csv"
why="rendered on $(tail -1 "$OUT/gpu.csv" | cut -d, -f1,2): the half-resolution depth on each half texel's own ray"
for m in ci gpu-cpu gpu; do
  flt=.; [ $m = gpu ] && flt='_fast/.*half/'
  .bundle/render.sh --matrix $m --filter "$flt" --out /tmp/render-$m > "$OUT/render-$m.log" 2>&1
  echo "render $m: rc $? ($(el) s)"; tail -1 "$OUT/render-$m.log"
  .bundle/cavity.sh baselines approve --from /tmp/render-$m --baselines baselines --store /tmp/store \
    --by half_ray_depth/gpu_call.sh --why "$m $why" > "$OUT/approve-$m.log" 2>&1
  echo "approve $m: rc $?"; tail -1 "$OUT/approve-$m.log"
  .bundle/cavity.sh gate judge /tmp/render-$m --baselines baselines --store /tmp/store --out /tmp/judge-$m --quiet \
    > "$OUT/judge-$m.md" 2>&1
  echo "judge $m after approval: rc $?"; head -4 "$OUT/judge-$m.md"
  cp baselines/approvals.json "$OUT/approvals.json"
done
echo "all: $(el) s"
