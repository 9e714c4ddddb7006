#!/usr/bin/env bash
# The separable blur's two passes as one (fused_blur=1), on the H200, in one call:
# 1. The fast kernels' configurations with and without it, full, half and
#    half with the fused tail, 10 interleaved repetitions, the clocks beside.
# 2. The same pipelines rendered both ways at 1920x1080 (matrices.json), each
#    pair's digests compared (digests.py).
set -uo pipefail
. scripts/gpu_env.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
D=lab/2026-12-04_h200_fused_blur
nvidia-smi --query-gpu=name,driver_version,clocks.max.sm --format=csv > $OUT/gpu.txt 2>&1
filter='^corner/(alchemy_fast|hemisphere_fast)/n(16|32)/b4/(fused_blur=1/)?full/1920x1080/(gl|vk)/compute/'
filter+='|^corner/(alchemy_fast|hemisphere_fast)/n16/b4/(fused_blur=1/)?((fused_tail=1/)?half)/1920x1080/(gl|vk)/compute/'
smi_start $OUT/targets.clocks.csv
.bundle/run.sh --sweep gpu --benchmark_filter="$filter" --benchmark_repetitions=10 \
  --benchmark_enable_random_interleaving=true --max-time 0.3 \
  --benchmark_out=$OUT/targets.json --benchmark_out_format=json > $OUT/targets.txt 2> $OUT/targets.err
echo "== targets: rc $? ($(el) s)"; smi_stop
python3 $D/table.py $OUT/targets.json | tee $OUT/table.md
gzip -f $OUT/targets.json
work=/tmp/fb; rm -rf $work; mkdir -p $work/base; cp $D/matrices.json $work/base/
smi_start $OUT/render.clocks.csv
timeout 250 .bundle/render.sh --matrix fused_blur --baselines $work/base --out $work/r > $OUT/render.txt 2>&1
echo "== render: rc $? ($(el) s)"; smi_stop
cp $work/r/manifest.json $OUT/manifest.json
python3 $D/digests.py $OUT/manifest.json | tee $OUT/digests.txt | tail -3
echo "all: $(el) s"
