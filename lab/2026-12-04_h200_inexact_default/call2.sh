#!/usr/bin/env bash
# 1. hemisphere_fast's points written out for GL (B, this build) against the
#    loop (A: ssao_hemisphere_fast_loop.glsl, the kernel before), cavity ab,
#    4 interleaved rounds, n16 and n32, both APIs.
# 2. The gpu matrix's hemisphere_fast pipelines rendered: digests against
#    baselines/approvals.json; those that moved approved, rendered again and
#    judged by digest.
# 3. The gpu-cpu matrix's alchemy_fast and hemisphere_fast pipelines rendered
#    on the H200; the render folder comes back to be judged against the
#    lavapipe baselines where OpenImageIO is (cavity gate judge).
# 4. The targets again, 10 interleaved repetitions, the clocks beside them.
set -uo pipefail
cd "$(dirname "$0")/../.."
. scripts/gpu_env.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
K=/tmp/keep; rm -rf $K; mkdir -p $K
A=lab/2026-12-04_h200_inexact_default/ssao_hemisphere_fast_loop.glsl   # the kernel as committed; B: hemisphere_written_out.patch applied
smi_start $K/ab.clocks.csv
.bundle/cavity.sh ab --a .bundle --b .bundle --rounds 4 \
  --filter '^corner/hemisphere_fast/n(16|32)/b4/full/1920x1080/(gl|vk)/compute/' \
  --bench-args='--sweep gpu --max-time 0.3' --a-args="--kernel-source ssao_hemisphere_fast.glsl=$A" \
  --out $K/ab > $K/ab.txt 2>&1
echo "== ab: rc $? ($(el) s)"; smi_stop
grep -E "compute +ao " $K/ab.txt | cut -c1-120
work=/tmp/refs; rm -rf $work; mkdir -p $work; cp -r baselines $work/base
smi_start $K/render.clocks.csv
.bundle/render.sh --matrix gpu --filter '/hemisphere_fast/' --baselines $work/base --out $work/r0 > $K/render0.txt 2>&1
echo "== render 0: rc $? ($(el) s); image files: $(find $work/r0 -name '*.f32z' | wc -l)"
cp $work/r0/manifest.json $K/manifest0.json
.bundle/cavity.sh baselines approve --from $work/r0 --baselines $work/base --by gpu_references.sh \
  --why "gpu matrix, hemisphere_fast with its points written out for GL, rendered on $(nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | head -1)" > $K/approve.txt 2>&1
echo "== approve: rc $? $(tail -1 $K/approve.txt)"
cp $work/base/approvals.json $K/approvals.json
.bundle/render.sh --matrix gpu --filter '_fast/' --baselines $work/base --out $work/r1 > $K/render1.txt 2>&1
echo "== render 1: rc $?; image files: $(find $work/r1 -name '*.f32z' | wc -l)"
.bundle/cavity.sh gate judge $work/r1 --baselines $work/base --out $work/g1 --quiet > $K/judge1.md 2>&1
echo "== judge 1: rc $? ($(el) s)"; head -3 $K/judge1.md; cp $work/g1/gate.json $K/judge1.json
.bundle/render.sh --matrix gpu-cpu --filter '/(alchemy_fast|hemisphere_fast)/' --baselines $work/base --out $K/gpu_cpu > $K/gpu_cpu.txt 2>&1
echo "== gpu-cpu render: rc $? ($(el) s)"
smi_stop
filter='^corner/(alchemy_fast|hemisphere_fast)/n(16|32)/b4/(exact=1/)?full/1920x1080/(gl|vk)/compute/'
filter+='|^corner/alchemy_fast/n16/b4/((fused_tail=1|exact=1)/)?half/1920x1080/(gl|vk)/compute/'
smi_start $K/clocks.csv
.bundle/run.sh --sweep gpu --benchmark_filter="$filter" --benchmark_repetitions=10 \
  --benchmark_enable_random_interleaving=true --max-time 0.3 \
  --benchmark_out=$K/targets.json --benchmark_out_format=json > $K/targets.txt 2> $K/targets.err
echo "== targets: rc $? ($(el) s)"
smi_stop
tar czf $OUT/call2.tgz -C /tmp keep; ls -la $OUT
echo "all: $(el) s"
