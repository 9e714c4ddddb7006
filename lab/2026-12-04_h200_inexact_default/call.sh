#!/usr/bin/env bash
# The fast kernels' default arithmetic is now the GPU's own (exact=0), on the
# H200, in one device call:
# 1. The targets: 10 interleaved repetitions of the default and exact=1
#    configurations, the clocks beside them.
# 2. The gpu matrix's alchemy_fast and hemisphere_fast pipelines rendered:
#    which digests moved against baselines/approvals.json (the exact
#    kernels'); approved for the H200 as gpu_references.sh does, then rendered
#    and judged again, by digest.
# 3. The gpu-cpu matrix's same pipelines on the H200, judged against the
#    (lavapipe) baselines by tolerance.
# 4. Quality: MAE after the blur against the ground truth, exact 0 and 1.
set -uo pipefail
cd "$(dirname "$0")/../.."
. scripts/gpu_env.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
K=/tmp/keep; rm -rf $K; mkdir -p $K
filter='^corner/(alchemy_fast|hemisphere_fast)/n(16|32)/b4/(exact=1/)?full/1920x1080/(gl|vk)/compute/'
filter+='|^corner/alchemy_fast/n16/b4/((fused_tail=1|exact=1)/)?half/1920x1080/(gl|vk)/compute/'
smi_start $K/clocks.csv
.bundle/run.sh --sweep gpu --benchmark_filter="$filter" --benchmark_repetitions=10 \
  --benchmark_enable_random_interleaving=true --max-time 0.3 \
  --benchmark_out=$K/targets.json --benchmark_out_format=json > $K/targets.txt 2> $K/targets.err
echo "== targets: rc $? ($(el) s)"
smi_stop
work=/tmp/refs; rm -rf $work; mkdir -p $work; cp -r baselines $work/base
sel='/(alchemy_fast|hemisphere_fast)/'
smi_start $K/render.clocks.csv
.bundle/render.sh --matrix gpu --filter "$sel" --baselines $work/base --out $work/r0 > $K/render0.txt 2>&1
echo "== render 0: rc $? ($(el) s); image files: $(find $work/r0 -name '*.f32z' | wc -l)"
cp $work/r0/manifest.json $K/manifest0.json
.bundle/cavity.sh baselines approve --from $work/r0 --baselines $work/base --by gpu_references.sh \
  --why "gpu matrix, alchemy_fast and hemisphere_fast with the GPU's own arithmetic (exact=0, now the default), rendered on $(nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | head -1)" > $K/approve.txt 2>&1
echo "== approve: rc $? $(tail -1 $K/approve.txt)"
cp $work/base/approvals.json $K/approvals.json
.bundle/render.sh --matrix gpu --filter "$sel" --baselines $work/base --out $work/r1 > $K/render1.txt 2>&1
echo "== render 1: rc $?; image files: $(find $work/r1 -name '*.f32z' | wc -l)"
.bundle/cavity.sh gate judge $work/r1 --baselines $work/base --out $work/g1 --quiet > $K/judge1.md 2>&1
echo "== judge 1: rc $? ($(el) s)"; head -3 $K/judge1.md; cp $work/g1/gate.json $K/judge1.json
.bundle/render.sh --matrix gpu-cpu --filter "$sel" --baselines $work/base --out $work/c0 > $K/cpu_render.txt 2>&1
echo "== gpu-cpu render: rc $? ($(el) s)"
.bundle/cavity.sh gate judge $work/c0 --baselines $work/base --out $work/cg --quiet > $K/cpu_judge.md 2>&1
echo "== gpu-cpu judge: rc $? ($(el) s)"; head -3 $K/cpu_judge.md; cp $work/cg/gate.json $K/cpu_judge.json
smi_stop
for e in 0 1; do for s in corner slats; do
  timeout 100 .bundle/render.sh quality --backend vk --res 1920x1080 --scene $s --kernel alchemy_fast,hemisphere_fast \
    --samples 16,32 --reach shared --blur 4 --exact $e --quiet --out $K/quality_exact${e}_$s > $K/quality_exact${e}_$s.txt 2>&1
  echo "== quality exact=$e $s: rc $? ($(el) s)"
done; done
tar czf $OUT/inexact.tgz -C /tmp keep; ls -la $OUT
echo "all: $(el) s"
