#!/usr/bin/env bash
# The G-buffer's linear depth (R32F) beside its positions, read by the depth
# pyramid and the downsample, on the H200 in one device call:
# 1. cavity ab: A the build before (.bundle2, cavity_bench alone), B this
#    one (.bundle), 4 interleaved rounds, the fast pipelines at 1920x1080.
# 2. The whole gpu matrix rendered: every image should be an approved digest
#    (no image file written); judged by digest.
# 3. The targets, 10 interleaved repetitions, the clocks beside them.
set -uo pipefail
cd "$(dirname "$0")/../.."
. scripts/gpu_env.sh
(cd .bundle2 && [ -x unpack.sh ] && ./unpack.sh)
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
K=/tmp/keep; rm -rf $K; mkdir -p $K
smi_start $K/ab.clocks.csv
.bundle/cavity.sh ab --a .bundle2 --b .bundle --rounds 4 \
  --filter '^corner/(alchemy_fast|hemisphere_fast)/n16/b4/full/1920x1080/(gl|vk)/compute/|^corner/alchemy_fast/n16/b4/(fused_tail=1/)?half/1920x1080/(gl|vk)/compute/' \
  --bench-args='--sweep gpu --max-time 0.3' --out $K/ab > $K/ab.txt 2>&1
echo "== ab: rc $? ($(el) s)"; smi_stop
grep -E "compute +(pipeline|pyramid|downsample|gbuffer|ao) " $K/ab.txt | cut -c1-125
work=/tmp/refs; rm -rf $work; mkdir -p $work; cp -r baselines $work/base
smi_start $K/render.clocks.csv
.bundle/render.sh --matrix gpu --baselines $work/base --out $work/r0 > $K/render0.txt 2>&1
echo "== render: rc $? ($(el) s); image files: $(find $work/r0 -name '*.f32z' | wc -l)"
find $work/r0 -name '*.f32z' | sed "s|$work/r0/images/||" | head -20
cp $work/r0/manifest.json $K/manifest.json
.bundle/cavity.sh gate judge $work/r0 --baselines $work/base --out $work/g0 --quiet > $K/judge.md 2>&1
echo "== judge: rc $? ($(el) s)"; head -3 $K/judge.md; cp $work/g0/gate.json $K/judge.json
smi_stop
filter='^corner/(alchemy_fast|hemisphere_fast)/n(16|32)/b4/(exact=1/)?full/1920x1080/(gl|vk)/compute/'
filter+='|^corner/alchemy_fast/n16/b4/((fused_tail=1|exact=1)/)?half/1920x1080/(gl|vk)/compute/'
smi_start $K/clocks.csv
.bundle/run.sh --sweep gpu --benchmark_filter="$filter" --benchmark_repetitions=10 \
  --benchmark_enable_random_interleaving=true --max-time 0.3 \
  --benchmark_out=$K/targets.json --benchmark_out_format=json > $K/targets.txt 2> $K/targets.err
echo "== targets: rc $? ($(el) s)"
smi_stop
tar czf $OUT/linear_depth.tgz -C /tmp keep; ls -la $OUT
echo "all: $(el) s"
