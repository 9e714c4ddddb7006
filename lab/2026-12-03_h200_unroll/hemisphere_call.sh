#!/usr/bin/env bash
# hemisphere_fast's points written out for GL, against the committed build.
set -uo pipefail
cd "$(dirname "$0")/.."
for f in .bundle/*.xz .bundle/lib/*.xz .bundle2/*.xz; do xz -d "$f"; done
cp .bundle2/cavity_bench .bundle/cavity_bench; chmod +x .bundle/cavity_bench .bundle/cavity
. scripts/gpu_env.sh
mkdir -p /tmp/keep
smi_start /tmp/keep/hemi_w.clocks.csv
.bundle/cavity.sh ab --a .bundle --b .bundle --rounds 4 --filter '^corner/hemisphere_fast/n(16|32)/b4/full/1920x1080/(gl|vk)/compute/' \
  --bench-args='--max-time 0.3' --b-args='--kernel-source ssao_hemisphere_fast.glsl=.old/v/hemi_w.glsl' --out /tmp/keep/hemi_w > /tmp/keep/hemi_w.txt 2>&1
echo "rc $?"
smi_stop
grep -E "compute  +(ao|pipeline) " /tmp/keep/hemi_w.txt | awk '{print $1, $2, $3, $4, $5, $NF}'
tar czf $OUT/hemi_w.tgz -C /tmp keep
