#!/usr/bin/env bash
# One device call, asked of the H200 the targets were set on (an H100 came):
# 1. The round-three targets (alchemy_fast n16/n32, hemisphere_fast,
#    ssdo_fast, gtao; full and the fused-tail half pipeline; both APIs)
#    with every timer/ probe, 10 interleaved repetitions, the clocks beside
#    them; the table against the floors and the launch fit for this GPU.
# 2. The CPU matrices (ci, gpu-cpu) and the gpu matrix's gtao configurations
#    (its blur is now the separable one) rendered here and approved by digest
#    for the nvidia-h200 class, then judged again against those approvals;
#    approvals.json and the CPU matrices' renders come back.
#   bash lab/2026-12-06_gpu_round3/call1.sh   (.gl and .bundle carried)
set -uo pipefail
cd "$(dirname "$0")/../.."
. scripts/gpu_env.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv > "$OUT/gpu.csv" 2>&1
cat "$OUT/gpu.csv"
f='^corner/(alchemy_fast|hemisphere_fast|gtao)/n16/b4/(full|fused_tail=1/half)/1920x1080/(gl|vk)/compute/'
f+='|^corner/alchemy_fast/n32/b4/full/1920x1080/(gl|vk)/compute/|^corner/ssdo_fast/n16/b4/full/1920x1080/(gl|vk)/compute/'
filter="$f|^timer/" reps=10 maxt=0.3 bench targets
echo "targets: rc $? ($(el) s)"
python3 lab/2026-12-04_h200_floors/floors.py "$OUT/targets.json" > "$OUT/floors.md" 2>&1; head -40 "$OUT/floors.md"
python3 lab/2026-12-06_gpu_packed_texel/launch_fit.py "$OUT/targets.json" > "$OUT/launch.md" 2>&1; cat "$OUT/launch.md"
gzip -f "$OUT/targets.json"
why="rendered on $(tail -1 "$OUT/gpu.csv" | cut -d, -f1,2): references of its own class"
for m in gpu ci gpu-cpu; do
  flt=.; [ $m = gpu ] && flt=/gtao/
  .bundle/render.sh --matrix $m --filter "$flt" --out /tmp/render-$m > "$OUT/render-$m.log" 2>&1
  echo "render $m: rc $? ($(el) s)"; tail -1 "$OUT/render-$m.log"
  .bundle/cavity.sh baselines approve --from /tmp/render-$m --baselines baselines --store /tmp/store \
    --why "$m $why" > "$OUT/approve-$m.log" 2>&1
  echo "approve $m: rc $?"; tail -1 "$OUT/approve-$m.log"
  .bundle/cavity.sh gate judge /tmp/render-$m --baselines baselines --store /tmp/store --out /tmp/judge-$m --quiet \
    > "$OUT/judge-$m.md" 2>&1
  echo "judge $m after approval: rc $?"; head -4 "$OUT/judge-$m.md"
done
cp baselines/approvals.json "$OUT/approvals.json"
tar -C /tmp -cf - render-ci render-gpu-cpu | xz -T0 -3 > "$OUT/renders.tar.xz"
s=$(stat -c %s "$OUT/renders.tar.xz"); echo "renders: $((s / 1048576)) MiB"
[ "$s" -gt 45000000 ] && { rm -f "$OUT/renders.tar.xz"; echo "renders too large to bring back"; }
echo "all: $(el) s"
