#!/usr/bin/env bash
# alchemy_fast with positionAt() in fused multiply-adds and its weight out of
# its sum (the default arithmetic, exact=0), on the H200, in one call:
# 1. cavity ab, 4 rounds: A = the build before the stored sources (.bundle2),
#    B = this one, the fast kernels' targets configurations.
# 2. The targets: 10 interleaved repetitions, the clocks beside them.
# 3. The gpu matrix's alchemy_fast pipelines rendered; their moved digests
#    approved for the H200 as gpu_references.sh does; rendered and judged again.
# 4. The gpu-cpu matrix's alchemy_fast pipelines rendered on the H200, the
#    render folder brought back to be judged against the lavapipe baselines here
#    (the bundle's cavity has no OpenImageIO to read them).
# 5. Quality: MAE after the blur against the ground truth, corner and slats, n16, n32.
set -uo pipefail
. scripts/gpu_env.sh
.bundle2/unpack.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
K=/tmp/keep; rm -rf $K; mkdir -p $K
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $K/gpu.txt 2>&1
filter='^corner/(alchemy_fast|hemisphere_fast)/n(16|32)/b4/full/1920x1080/(gl|vk)/compute/'
filter+='|^corner/(alchemy_fast|hemisphere_fast)/n16/b4/((fused_tail=1/)?half)/1920x1080/(gl|vk)/compute/'
smi_start $K/ab.clocks.csv
.bundle/cavity.sh ab --a .bundle2 --b .bundle --rounds 4 --filter "$filter" \
  --bench-args='--sweep gpu --max-time 0.3' --out $K/ab > $K/ab.txt 2>&1
echo "== ab: rc $? ($(el) s)"; smi_stop
grep -E "n16/b4/full.*compute +(pipeline|ao|pyramid) " $K/ab.txt | cut -c1-125
smi_start $K/targets.clocks.csv
.bundle/run.sh --sweep gpu --benchmark_filter="$filter" --benchmark_repetitions=10 \
  --benchmark_enable_random_interleaving=true --max-time 0.3 \
  --benchmark_out=$K/targets.json --benchmark_out_format=json > $K/targets.txt 2> $K/targets.err
echo "== targets: rc $? ($(el) s)"; smi_stop
work=/tmp/refs; rm -rf $work; mkdir -p $work; cp -r baselines $work/base
sel='/alchemy_fast/'
smi_start $K/render.clocks.csv
.bundle/render.sh --matrix gpu --filter "$sel" --baselines $work/base --out $work/r0 > $K/render0.txt 2>&1
echo "== render 0: rc $? ($(el) s)"; cp $work/r0/manifest.json $K/manifest0.json
.bundle/cavity.sh baselines approve --from $work/r0 --baselines $work/base --by gpu_references.sh \
  --why "gpu matrix, alchemy_fast with positionAt() in fused multiply-adds and its weight out of its sum (exact=0, the default), rendered on $(nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | head -1)" > $K/approve.txt 2>&1
echo "== approve: rc $? $(tail -1 $K/approve.txt)"
cp $work/base/approvals.json $K/approvals.json
.bundle/render.sh --matrix gpu --filter "$sel" --baselines $work/base --out $work/r1 > $K/render1.txt 2>&1
echo "== render 1: rc $?"
.bundle/cavity.sh gate judge $work/r1 --baselines $work/base --out $work/g1 --quiet > $K/judge1.md 2>&1
echo "== judge 1: rc $? ($(el) s)"; head -3 $K/judge1.md; cp $work/g1/gate.json $K/judge1.json
.bundle/render.sh --matrix gpu-cpu --filter "$sel" --baselines $work/base --out $K/cpu_render > $K/cpu_render.txt 2>&1
echo "== gpu-cpu render: rc $? ($(el) s)"
smi_stop
for s in corner slats; do
  timeout 100 .bundle/render.sh quality --backend vk --res 1920x1080 --scene $s --kernel alchemy_fast \
    --samples 16,32 --reach shared --blur 4 --quiet --out $K/quality_$s > $K/quality_$s.txt 2>&1
  echo "== quality $s: rc $? ($(el) s)"
done
tar czf $OUT/call2.tgz -C /tmp keep; ls -la $OUT
echo "all: $(el) s"
