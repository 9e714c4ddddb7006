#!/usr/bin/env bash
# The last kernels (GL's samples written out, hemisphere_fast specialised)
# against the build before them, interleaved (cavity ab), then the targets
# with 10 interleaved repetitions.
set -uo pipefail
cd "$(dirname "$0")/.."
for f in .bundle/*.xz .bundle/lib/*.xz .bundle2/*.xz; do xz -d "$f"; done
chmod +x .bundle/cavity_bench .bundle/cavity .bundle/cavity_render .bundle2/cavity_bench
. scripts/gpu_env.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
mkdir -p /tmp/keep
smi_start /tmp/keep/ab.clocks.csv
.bundle/cavity.sh ab --a .bundle --b .bundle2 --rounds 4 \
  --filter '^corner/(alchemy_fast|hemisphere_fast|ssdo_fast)/n(16|32)/b4/full/1920x1080/(gl|vk)/compute/' \
  --bench-args='--max-time 0.3' --out /tmp/keep/final_ab > /tmp/keep/final_ab.txt 2>&1
echo "== ab: rc $? ($(el) s)"
smi_stop
grep -E "compute  +(ao|direct|indirect|pipeline) " /tmp/keep/final_ab.txt | awk '{print $1, $2, $3, $4, $5, $NF}'
cp .bundle2/cavity_bench .bundle/cavity_bench
filter='^corner/(alchemy_fast|hemisphere_fast)/n(16|32)/b4/((exact=0|pyramid_per_level=1|interleave=4)/)?full/1920x1080/(gl|vk)/compute/'
filter+='|^corner/(alchemy|alchemy_fast|hemisphere_fast)/n16/b4/((fused_tail=1|interleave=4)/)?half/1920x1080/(gl|vk)/compute/'
smi_start /tmp/keep/clocks.csv
.bundle/run.sh --sweep gpu --benchmark_filter="$filter" --benchmark_repetitions=10 \
  --benchmark_enable_random_interleaving=true --max-time 0.3 \
  --benchmark_out=/tmp/keep/kernels2.json --benchmark_out_format=json > /tmp/keep/kernels2.txt 2> /tmp/keep/kernels2.err
echo "== kernels2: rc $? ($(el) s)"
smi_stop
tar czf $OUT/all.tgz -C /tmp keep
echo "all: $(el) s"
