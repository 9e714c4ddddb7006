#!/usr/bin/env bash
# One device call. The H100's class holds approvals of 130 of the 132 ci and
# 188 of the 220 gpu-cpu configurations (study 2026-12-06_gpu_round3); the
# rest were left out by `baselines approve`, which skips a configuration with
# a render error or repetitions that differ. This renders both matrices again,
# lists what approve leaves out and why (errors.py), approves the rest for
# the device's class, and brings back the manifests, the errors, the render
# logs and approvals.json in one archive. On an H200 it first measures the
# round-three targets as study 2026-12-06_gpu_round3's call2 did.
#   bash lab/2026-12-06_gpu_render_errors/call1.sh   (.gl and .bundle carried)
set -uo pipefail
cd "$(dirname "$0")/../.."
. scripts/gpu_env.sh
here=lab/2026-12-06_gpu_render_errors
w=/tmp/r4; rm -rf $w; mkdir -p $w
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv > $w/gpu.csv 2>&1
cat $w/gpu.csv
name=$(tail -1 $w/gpu.csv | cut -d, -f1)
if [[ "$name" == *H200* ]]; then
  f='^corner/(alchemy_fast|hemisphere_fast|gtao)/n16/b4/(full|fused_tail=1/half)/1920x1080/(gl|vk)/compute/'
  f+='|^corner/alchemy_fast/n32/b4/full/1920x1080/(gl|vk)/compute/|^corner/ssdo_fast/n16/b4/full/1920x1080/(gl|vk)/compute/'
  OUT=$w filter="$f|^timer/" reps=10 maxt=0.3 bench targets
  echo "targets: rc $? ($(el) s)"
  python3 lab/2026-12-04_h200_floors/floors.py $w/targets.json > $w/floors.md 2>&1; head -30 $w/floors.md
  python3 lab/2026-12-06_gpu_packed_texel/launch_fit.py $w/targets.json > $w/launch.md 2>&1
  gzip -f $w/targets.json
fi
why="rendered on $(tail -1 $w/gpu.csv | cut -d, -f1,2): references of its own class"
for m in ci gpu-cpu; do
  .bundle/render.sh --matrix $m --out /tmp/render-$m > $w/render-$m.log 2>&1
  echo "render $m: rc $? ($(el) s)"; tail -2 $w/render-$m.log
  python3 $here/errors.py /tmp/render-$m > $w/left-out-$m.txt 2>&1; head -12 $w/left-out-$m.txt
  cp /tmp/render-$m/manifest.json $w/manifest-$m.json
  .bundle/cavity.sh baselines approve --from /tmp/render-$m --baselines baselines --store /tmp/store \
    --why "$m $why" > $w/approve-$m.log 2>&1
  echo "approve $m: rc $?"; tail -2 $w/approve-$m.log
done
cp baselines/approvals.json $w/approvals.json
gzip -f $w/manifest-*.json $w/render-*.log
tar -C /tmp -cf "$OUT/r4.tar" r4
echo "all: $(el) s, $(du -sh "$OUT/r4.tar" | cut -f1)"
