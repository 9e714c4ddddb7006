#!/usr/bin/env bash
# The unrolled sample loops and the written-out pyramid links against the
# targets (10 interleaved repetitions), and GL with the samples written out.
set -uo pipefail
cd "$(dirname "$0")/.."
for f in .bundle/*.xz .bundle/lib/*.xz; do xz -d "$f"; done
chmod +x .bundle/cavity_bench .bundle/cavity .bundle/cavity_render
. scripts/gpu_env.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
mkdir -p /tmp/keep
smi_start /tmp/keep/ab.clocks.csv
.bundle/cavity.sh ab --a .bundle --b .bundle --rounds 4 --filter '^corner/alchemy_fast/n16/b4/full/1920x1080/(gl|vk)/compute/' \
  --bench-args='--max-time 0.3' --b-args='--kernel-source ssao_alchemy_fast.glsl=.old/v/ao16w.glsl' --out /tmp/keep/written > /tmp/keep/written.txt 2>&1
echo "== written: rc $? ($(el) s)"
smi_stop
grep -E "compute  +(ao|pipeline) " /tmp/keep/written.txt | awk '{print $1, $2, $3, $4, $5, $NF}'
bash lab/scripts/gpu_kernels2.sh 10 0.3 2>&1 | tail -12
mv $OUT/kernels2.tgz /tmp/keep/
tar czf $OUT/all.tgz -C /tmp keep
echo "all: $(el) s"
