#!/usr/bin/env bash
# The round-three targets and the H200's references in one call, and only
# on an H200 (any other card: exit 3, nothing measured):
# 1. the targets of 2026-12-06_gpu_round3/call2.sh (10 interleaved
#    repetitions, clocks beside them, floors and launch fit) into targets.tgz;
# 2. the gpu, ci and gpu-cpu matrices rendered, their digests approved for
#    the nvidia-h200 class through a folder store (as a user would), and each
#    render judged against those approvals; approvals.json, the manifests and
#    the judges' summaries come back in refs.tgz. The gpu matrix is rendered
#    and judged a second time when the call's time allows.
#   bash lab/2026-12-07_h200_targets/call2.sh   (.gl and a full .bundle carried)
set -uo pipefail
cd "$(dirname "$0")/../.."
name=$(nvidia-smi --query-gpu=name --format=csv,noheader 2>&1 | head -1)
echo "card: $name"
case "$name" in *H200*) ;; *) echo "not an H200: nothing measured"; exit 3 ;; esac
. scripts/gpu_env.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
K=/tmp/keep; R=/tmp/refs; rm -rf $K $R; mkdir -p $K $R
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv > $K/gpu.csv 2>&1
cat $K/gpu.csv; cp $K/gpu.csv $R/
f='^corner/(alchemy_fast|hemisphere_fast|gtao)/n16/b4/(full|fused_tail=1/half)/1920x1080/(gl|vk)/compute/'
f+='|^corner/alchemy_fast/n32/b4/full/1920x1080/(gl|vk)/compute/|^corner/ssdo_fast/n16/b4/full/1920x1080/(gl|vk)/compute/'
filter="$f|^timer/" reps=10 maxt=0.3 OUT=$K bench targets
echo "targets: rc $? ($(el) s)"
python3 lab/2026-12-04_h200_floors/floors.py $K/targets.json > $K/floors.md 2>&1; head -30 $K/floors.md
python3 lab/2026-12-06_gpu_packed_texel/launch_fit.py $K/targets.json > $K/launch.md 2>&1; tail -3 $K/launch.md
gzip -f $K/targets.json $K/targets.clocks.csv
tar -C /tmp -czf "$OUT/targets.tgz" keep
why="rendered on $(tail -1 $K/gpu.csv | cut -d, -f1,2): references of its own class"
smi_start $R/refs.clocks.csv
for m in gpu ci gpu-cpu; do
  .bundle/render.sh --matrix $m --out /tmp/render-$m > $R/render-$m.log 2>&1
  echo "render $m: rc $? ($(el) s)"; tail -1 $R/render-$m.log
  .bundle/cavity.sh baselines approve --from /tmp/render-$m --baselines baselines --store /tmp/store \
    --by h200_targets/call2.sh --why "$m $why" > $R/approve-$m.log 2>&1
  echo "approve $m: rc $?"; tail -1 $R/approve-$m.log
  .bundle/cavity.sh gate judge /tmp/render-$m --baselines baselines --out /tmp/judge-$m --quiet > $R/judge-$m.md 2>&1
  echo "judge $m after approval: rc $?"; head -4 $R/judge-$m.md
  gzip -c /tmp/render-$m/manifest.json > $R/manifest-$m.json.gz
  cp /tmp/judge-$m/gate.json $R/gate-$m.json 2>/dev/null
  cp baselines/approvals.json $R/approvals.json
  tar -C /tmp -czf "$OUT/refs.tgz" refs
done
if [ "$(el)" -lt 380 ]; then
  .bundle/render.sh --matrix gpu --out /tmp/render-gpu2 > $R/render-gpu2.log 2>&1
  echo "render gpu again: rc $? ($(el) s)"
  .bundle/cavity.sh gate judge /tmp/render-gpu2 --baselines baselines --out /tmp/judge-gpu2 --quiet > $R/judge-gpu2.md 2>&1
  echo "judge gpu again: rc $?"; head -4 $R/judge-gpu2.md
fi
smi_stop; gzip -f $R/refs.clocks.csv
tar -C /tmp -czf "$OUT/refs.tgz" refs
ls -la "$OUT"; echo "all: $(el) s"
