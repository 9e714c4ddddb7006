#!/usr/bin/env bash
# ssdo_fast's direct and bounce passes with a copy of their loops below the
# tiny levels (B, --kernel-source) against the build as it is (A).
set -uo pipefail
cd "$(dirname "$0")/../.."
for f in .bundle/*.xz .bundle/lib/*.xz; do xz -d "$f"; done
chmod +x .bundle/cavity_bench .bundle/cavity
. scripts/gpu_env.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
K=/tmp/keep; mkdir -p $K
smi_start $K/ssdo.clocks.csv
.bundle/cavity.sh ab --a .bundle --b .bundle --rounds 4 \
  --filter '^corner/ssdo_fast/n(16|32)/b4/full/1920x1080/(gl|vk)/compute/' --bench-args='--max-time 0.3' \
  --b-args="--kernel-source ssdo_fast_direct.glsl=.old/ssdo/ssdo_fast_direct.glsl --kernel-source ssdo_fast_indirect.glsl=.old/ssdo/ssdo_fast_indirect.glsl" \
  --out $K/ssdo > $K/ssdo.txt 2>&1
echo "== ssdo: rc $? ($(el) s)"; smi_stop
grep -E "compute  +[a-z_]+ " $K/ssdo.txt | awk '{print $1,$2,$3,$4,$5,$NF}'
tar czf $OUT/ssdo.tgz -C /tmp keep
