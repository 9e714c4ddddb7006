#!/usr/bin/env bash
# One device call: the pyramid's 32-bit texel (this build, .bundle) against
# the 8-byte one it replaced (.bundle_old, the build before), and the launch
# probes the floor's launch term is fitted to.
# 1. The targets with this build, 10 interleaved repetitions, both APIs,
#    with every timer/ probe (the empty dispatch at five sizes).
# 2. cavity ab, old against new, 4 rounds, the same configurations.
# 3. The gpu matrix's fast-kernel configurations rendered, judged against
#    the approvals as committed (which changed?), approved for this device's
#    class, judged again; approvals.json comes back.
# 4. With time left, the CPU matrices (ci, gpu-cpu) rendered and approved
#    for this class too, their renders back (the GPU against the CPU
#    baselines: lab 2026-12-06_h200_cpu_matrices).
#   bash lab/2026-12-06_gpu_packed_texel/call1.sh   (.gl, .bundle, .bundle_old carried)
set -uo pipefail
cd "$(dirname "$0")/../.."
. scripts/gpu_env.sh
[ -x .bundle_old/unpack.sh ] && .bundle_old/unpack.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
K=/tmp/keep; rm -rf $K; mkdir -p $K
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv > $K/gpu.csv 2>&1
cat $K/gpu.csv
f='^corner/(alchemy_fast|hemisphere_fast|gtao)/n16/b4/(full|fused_tail=1/half)/1920x1080/(gl|vk)/compute/'
f+='|^corner/alchemy_fast/n32/b4/full/1920x1080/(gl|vk)/compute/|^corner/ssdo_fast/n16/b4/full/1920x1080/(gl|vk)/compute/'
filter="$f|^timer/" reps=10 maxt=0.3 OUT=$K bench targets
echo "targets: rc $? ($(el) s)"
python3 lab/2026-12-04_h200_floors/floors.py $K/targets.json > $K/floors.md 2>&1; head -40 $K/floors.md
python3 lab/2026-12-06_gpu_packed_texel/launch_fit.py $K/targets.json > $K/launch.md 2>&1; cat $K/launch.md
smi_start $K/ab.clocks.csv
.bundle/cavity.sh ab --a .bundle_old --b .bundle --rounds 4 --filter "$f" --bench-args='--sweep gpu --max-time 0.3' \
  --out $K/ab > $K/ab.txt 2>&1
echo "ab: rc $? ($(el) s)"; smi_stop
grep -E "compute +(pyramid|downsample|ao|blur_x|blur_y|upsample_composite|composite|direct|indirect|pipeline) " $K/ab.txt | cut -c1-160 | head -60
work=/tmp/refs; rm -rf $work; mkdir -p $work; cp -r baselines $work/base
class_why="the pyramid packs its source pixel into a 32-bit texel: $(tail -1 $K/gpu.csv)"
render_judge_approve() {   # MATRIX FILTER
  local m=$1 flt=$2
  .bundle/render.sh --matrix $m --filter "$flt" --baselines $work/base --out $work/r_$m > $K/render_$m.log 2>&1
  echo "render $m: rc $? ($(el) s)"; tail -1 $K/render_$m.log
  .bundle/cavity.sh gate judge $work/r_$m --baselines $work/base --out $work/g_$m --quiet > $K/judge_before_$m.md 2>&1
  echo "judge before $m: rc $?"; head -5 $K/judge_before_$m.md
  .bundle/cavity.sh baselines approve --from $work/r_$m --baselines $work/base --store /tmp/store \
    --why "$m: $class_why" > $K/approve_$m.log 2>&1
  echo "approve $m: rc $?"; tail -1 $K/approve_$m.log
  .bundle/cavity.sh gate judge $work/r_$m --baselines $work/base --out $work/g2_$m --quiet > $K/judge_after_$m.md 2>&1
  echo "judge after $m: rc $?"; head -3 $K/judge_after_$m.md
}
render_judge_approve gpu '_fast/'
cp $work/base/approvals.json $K/approvals.json
if [ "$(el)" -lt 330 ]; then
  render_judge_approve ci '.'
  render_judge_approve gpu-cpu '.'
  cp $work/base/approvals.json $K/approvals.json
  tar -C $work -cf - r_ci r_gpu-cpu | xz -T0 -3 > $K/cpu_matrix_renders.tar.xz
  ls -la $K/cpu_matrix_renders.tar.xz
fi
gzip -f $K/targets.json
tar -C /tmp -czf $OUT/call1.tgz keep; ls -la $OUT; echo "all: $(el) s"
