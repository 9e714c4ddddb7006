#!/usr/bin/env bash
# The blur's two changes kept, on the H200, in one call:
# 1. cavity ab, 4 rounds: A = the build before (.bundle2: cavity_bench of
#    3e24a73), B = the separable blur's background tap as a select and
#    ssdo_fast's horizontal blur with its radiance in the tile (.bundle),
#    alchemy_fast and hemisphere_fast n16 full and half with the fused
#    tail, ssdo_fast n16, both APIs.
#    Then a probe of the upsample (1b).
# 2. The whole gpu matrix rendered with B and judged by digest.
# 3. The targets with B, 10 interleaved repetitions, every pass against its
#    floor, the clocks beside them.
set -uo pipefail
. scripts/gpu_env.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
D=lab/2026-12-04_h200_floors
K=/tmp/keep; rm -rf $K; mkdir -p $K
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $K/gpu.txt 2>&1
abf='^corner/(alchemy_fast|hemisphere_fast)/n16/b4/(full|fused_tail=1/half)/1920x1080/(gl|vk)/compute/'
abf+='|^corner/ssdo_fast/n16/b4/full/1920x1080/(gl|vk)/compute/'
smi_start $K/ab.clocks.csv
.bundle/cavity.sh ab --a .bundle2 --b .bundle --rounds 4 --filter "$abf" \
  --bench-args='--sweep gpu --max-time 0.3' --out $K/ab > $K/ab.txt 2>&1
echo "== ab: rc $? ($(el) s)"; smi_stop
grep -E "compute +(blur_x|blur_y|indirect_blur_x|indirect_blur_y|pipeline) " $K/ab.txt | cut -c1-150
# 1b. A probe: the upsample's background texel weighed 0 by a select, where
#     a branch skipped it (upsample_select.glsl, include/upsample.glsl; the
#     same digests on the CPU renderers, 132 of 132), B against B.
abf='^corner/(alchemy_fast|hemisphere_fast)/n16/b4/(fused_tail=1/)?half/1920x1080/(gl|vk)/compute/'
smi_start $K/ab_upsample.clocks.csv
.bundle/cavity.sh ab --a .bundle --b .bundle --rounds 4 --filter "$abf" --bench-args='--sweep gpu --max-time 0.3' \
  --b-args="--kernel-source include/upsample.glsl=$D/upsample_select.glsl" --out $K/ab_upsample > $K/ab_upsample.txt 2>&1
echo "== ab upsample: rc $? ($(el) s)"; smi_stop
grep -E "compute +(upsample|upsample_composite|pipeline) " $K/ab_upsample.txt | cut -c1-150
work=/tmp/refs; rm -rf $work; mkdir -p $work; cp -r baselines $work/base
.bundle/render.sh --matrix gpu --filter half --kernel-source include/upsample.glsl=$D/upsample_select.glsl \
  --baselines $work/base --out $work/r_upsample > $K/render_upsample.txt 2>&1
.bundle/cavity.sh gate judge $work/r_upsample --baselines $work/base --out $work/g_upsample --quiet > $K/judge_upsample.md 2>&1
echo "== judge upsample: rc $?"; head -3 $K/judge_upsample.md
.bundle/render.sh --matrix gpu --baselines $work/base --out $work/r > $K/render.txt 2>&1
echo "== render: rc $? ($(el) s)"; tail -1 $K/render.txt
.bundle/cavity.sh gate judge $work/r --baselines $work/base --out $work/g --quiet > $K/judge.md 2>&1
echo "== judge: rc $?"; head -3 $K/judge.md
filter='^corner/(alchemy_fast|hemisphere_fast)/n(16|32)/b4/full/1920x1080/(gl|vk)/compute/'
filter+='|^corner/(alchemy_fast|hemisphere_fast)/n16/b4/((fused_tail=1/)?half)/1920x1080/(gl|vk)/compute/'
filter+='|^corner/ssdo_fast/n16/b4/full/1920x1080/(gl|vk)/compute/'
smi_start $K/targets.clocks.csv
.bundle/run.sh --sweep gpu --benchmark_filter="$filter" --benchmark_repetitions=10 \
  --benchmark_enable_random_interleaving=true --max-time 0.3 \
  --benchmark_out=$K/targets.json --benchmark_out_format=json > $K/targets.txt 2> $K/targets.err
echo "== targets: rc $? ($(el) s)"; smi_stop
python3 lab/2026-12-04_h200_inexact_default/table.py $K/targets.json > $K/table.md 2>&1
python3 $D/floors.py $K/targets.json > $K/floors.md 2>&1
head -12 $K/table.md; tail -3 $K/floors.md
gzip -f $K/targets.json
tar czf $OUT/call2.tgz -C /tmp keep; echo "all: $(el) s"
