#!/usr/bin/env bash
# The final build: the gpu matrix's fast compute pipelines rendered and
# judged by digest (baselines/approvals.json as committed), then the
# targets with 10 interleaved repetitions, the clocks beside them.
set -uo pipefail
cd "$(dirname "$0")/../.."
for f in .bundle/*.xz .bundle/lib/*.xz; do xz -d "$f"; done
chmod +x .bundle/cavity_bench .bundle/cavity .bundle/cavity_render
. scripts/gpu_env.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
K=/tmp/keep; mkdir -p $K
smi_start $K/render.clocks.csv
.bundle/render.sh --matrix gpu --filter '_fast/.*/compute$' --out /tmp/r > $K/render.txt 2>&1
echo "== render: rc $? ($(el) s); image files: $(find /tmp/r -name '*.f32z' | wc -l)"
.bundle/cavity.sh gate judge /tmp/r --out /tmp/g --quiet > $K/judge.md 2>&1
echo "== judge: rc $?"; head -3 $K/judge.md; cp /tmp/g/gate.json $K/judge.json; cp /tmp/r/manifest.json $K/manifest.json
smi_stop
filter='^corner/(alchemy_fast|hemisphere_fast)/n(16|32)/b4/full/1920x1080/(gl|vk)/compute/'
filter+='|^corner/(alchemy_fast|hemisphere_fast)/n16/b4/exact=0/full/1920x1080/(gl|vk)/compute/'
filter+='|^corner/alchemy_fast/n16/b4/(fused_tail=1/)?half/1920x1080/(gl|vk)/compute/'
smi_start $K/clocks.csv
.bundle/run.sh --sweep gpu --benchmark_filter="$filter" --benchmark_repetitions=10 \
  --benchmark_enable_random_interleaving=true --max-time 0.3 \
  --benchmark_out=$K/kernels2.json --benchmark_out_format=json > $K/kernels2.txt 2> $K/kernels2.err
echo "== kernels2: rc $? ($(el) s)"
smi_stop
tar czf $OUT/confirm.tgz -C /tmp keep
echo "all: $(el) s"
