#!/usr/bin/env bash
# The separable blur in 32x8 (x) and 8x32 (y) workgroups (B, .bundle2)
# against 16x16 (A, .bundle), interleaved.
set -uo pipefail
cd "$(dirname "$0")/../.."
for f in .bundle/*.xz .bundle/lib/*.xz .bundle2/*.xz .bundle2/lib/*.xz; do xz -d "$f"; done
chmod +x .bundle/cavity_bench .bundle/cavity .bundle2/cavity_bench
. scripts/gpu_env.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
K=/tmp/keep; mkdir -p $K
smi_start $K/shape.clocks.csv
.bundle/cavity.sh ab --a .bundle --b .bundle2 --rounds 4 \
  --filter '^corner/(alchemy_fast/n16/b4/((fused_tail=1/)?half|full)|ssdo_fast/n16/b4/full)/1920x1080/(gl|vk)/compute/' \
  --bench-args='--sweep gpu --max-time 0.3' --out $K/shape > $K/shape.txt 2>&1
echo "== shape: rc $? ($(el) s)"; smi_stop
grep -E "compute  +[a-z_]+ " $K/shape.txt | grep -E " (blur_x|blur_y|pipeline) " | cut -c1-112
tar czf $OUT/shape.tgz -C /tmp keep
echo "all: $(el) s"
