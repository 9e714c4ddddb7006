#!/usr/bin/env bash
# One call on the H200:
# 1. Three probes of the separable blur's taps by --kernel-source
#    (include/blur_separable.glsl), each cavity ab's B against B, 4 rounds,
#    alchemy_fast n16 full and half with the fused tail, both APIs:
#    blur_select.glsl (the background test a select), blur_rcp.glsl (the
#    depth term's division out of the taps: exp2 of dd^2 times a constant
#    computed once a pixel), blur_noexp.glsl (no depth term: wrong images,
#    what it costs).
#    ssdo_fast n16 with its radiance tiled beside the key.
# 2. blur_rcp's images against the approved digests (the gpu matrix's
#    alchemy_fast configurations), and the radiance tile's (ssdo_fast's).
# 3. The targets, 10 interleaved repetitions, with the floors of the tiled
#    passes as they now count, the clocks beside them, ssdo_fast n16.
# 4. hemisphere_fast's and ssdo_fast's configurations of the gpu matrix
#    judged by digest (their kernels' macros were rewritten).
set -uo pipefail
. scripts/gpu_env.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
D=lab/2026-12-04_h200_floors
K=/tmp/keep; rm -rf $K; mkdir -p $K
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $K/gpu.txt 2>&1
abf='^corner/alchemy_fast/n16/b4/(full|fused_tail=1/half)/1920x1080/(gl|vk)/compute/'
probe() {   # NAME KERNEL_SOURCE
  smi_start $K/ab_$1.clocks.csv
  .bundle/cavity.sh ab --a .bundle --b .bundle --rounds 4 --filter "$abf" \
    --bench-args='--sweep gpu --max-time 0.3' --b-args="--kernel-source $2" --out $K/ab_$1 > $K/ab_$1.txt 2>&1
  echo "== ab $1: rc $? ($(el) s)"; smi_stop
  grep -E "compute +(blur_x|blur_y|pipeline) " $K/ab_$1.txt | cut -c1-150
}
for p in select rcp noexp; do probe $p include/blur_separable.glsl=$D/blur_$p.glsl; done
# 1b. ssdo_fast's blurs with the radiance in the tile beside the key
#     (radiance_tile_*.glsl: the three files as the working tree has them).
abf='^corner/ssdo_fast/n16/b4/full/1920x1080/(gl|vk)/compute/'
smi_start $K/ab_radiance.clocks.csv
.bundle/cavity.sh ab --a .bundle --b .bundle --rounds 4 --filter "$abf" --bench-args='--sweep gpu --max-time 0.3' \
  --b-args="--kernel-source include/blur_separable.glsl=$D/radiance_tile_blur_separable.glsl --kernel-source blur_separable_ssdo_x.glsl=$D/radiance_tile_ssdo_x.glsl --kernel-source blur_separable_ssdo_y.glsl=$D/radiance_tile_ssdo_y.glsl" \
  --out $K/ab_radiance > $K/ab_radiance.txt 2>&1
echo "== ab radiance: rc $? ($(el) s)"; smi_stop
grep -E "compute +(blur_x|blur_y|indirect_blur_x|indirect_blur_y|pipeline) " $K/ab_radiance.txt | cut -c1-150
work=/tmp/refs; rm -rf $work; mkdir -p $work; cp -r baselines $work/base
judge() {   # NAME FILTER [render args]
  local n=$1 f=$2; shift 2
  .bundle/render.sh --matrix gpu --filter "$f" "$@" --baselines $work/base --out $work/r_$n > $K/render_$n.txt 2>&1
  echo "== render $n: rc $? ($(el) s)"; tail -1 $K/render_$n.txt
  .bundle/cavity.sh gate judge $work/r_$n --baselines $work/base --out $work/g_$n --quiet > $K/judge_$n.md 2>&1
  echo "== judge $n: rc $?"; head -3 $K/judge_$n.md
}
judge rcp '/alchemy_fast/' --kernel-source include/blur_separable.glsl=$D/blur_rcp.glsl
judge radiance '/ssdo_fast/' --kernel-source include/blur_separable.glsl=$D/radiance_tile_blur_separable.glsl \
  --kernel-source blur_separable_ssdo_x.glsl=$D/radiance_tile_ssdo_x.glsl --kernel-source blur_separable_ssdo_y.glsl=$D/radiance_tile_ssdo_y.glsl
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
judge refactor '/(hemisphere_fast|ssdo_fast)/'
tar czf $OUT/call1.tgz -C /tmp keep; echo "all: $(el) s"
