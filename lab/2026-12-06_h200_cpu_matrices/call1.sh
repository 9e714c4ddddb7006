#!/usr/bin/env bash
# The CPU matrices (ci, gpu-cpu) rendered on the H200 and approved by digest
# for its device class, so that an H200 judges them against its own
# references instead of the lavapipe baselines under NVIDIA overrides; the
# render folders come back too, to measure here how far the H200 is from the
# CPU baselines (the cross-device noise a gate metric must stay above).
#   bash lab/2026-12-06_h200_cpu_matrices/call1.sh   (on the GPU machine, .gl and .bundle carried)
set -uo pipefail
cd "$(dirname "$0")/../.."
. scripts/gpu_env.sh
start=$(date +%s)
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv > "$OUT/gpu.csv" 2>&1
for m in ci gpu-cpu; do
  .bundle/render.sh --matrix $m --out /tmp/render-$m > "$OUT/render-$m.log" 2>&1
  echo "render $m rc=$? ($(( $(date +%s) - start )) s)"
  .bundle/cavity.sh baselines approve --from /tmp/render-$m --baselines baselines --store /tmp/store \
    --why "$m rendered on NVIDIA H200, driver 580.159.04: references of its own class" > "$OUT/approve-$m.log" 2>&1
  echo "approve $m rc=$?"; tail -1 "$OUT/approve-$m.log"
done
cp baselines/approvals.json "$OUT/approvals.json"
# The renders back, under 15 MiB a part, at most 6 parts.
tar -C /tmp -cf - render-ci render-gpu-cpu | split -b 15M -d - "$OUT/renders.tar."
ls -la "$OUT"/renders.tar.* | awk '{s+=$5} END {print "renders:", NR, "parts,", s/1048576, "MiB"}'
n=$(ls "$OUT"/renders.tar.* | wc -l)
if [ "$n" -gt 6 ]; then rm -f "$OUT"/renders.tar.*; echo "renders too large to bring back"; fi
echo "done ($(( $(date +%s) - start )) s)"
