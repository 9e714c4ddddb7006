#!/usr/bin/env bash
# Every pass in 16x16 workgroups (the three 8x8 passes between the two
# resolutions change: downsample, upsample, fused tail), and every pass in
# 32x8, against the declared shapes; cavity ab, B a wrapper that sets
# CAVITY_WORKGROUP around the same cavity_bench.
set -uo pipefail
cd "$(dirname "$0")/../.."
for f in .bundle/*.xz .bundle/lib/*.xz; do xz -d "$f"; done
chmod +x .bundle/cavity_bench .bundle/cavity .bundle/cavity_render
. scripts/gpu_env.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
K=/tmp/keep; mkdir -p $K
for s in 16x16 32x8; do
  smi_start $K/wg_$s.clocks.csv
  .bundle/cavity.sh ab --a .bundle --b lab/2026-12-03_h200_blur_tile/wg_$s.sh --rounds 4 \
    --filter '^corner/alchemy_fast/n16/b4/((fused_tail=1/)?half|full)/1920x1080/(gl|vk)/compute/' \
    --bench-args='--sweep gpu --max-time 0.3' --out $K/wg_$s > $K/wg_$s.txt 2>&1
  echo "== $s: rc $? ($(el) s)"; smi_stop
  grep -E "compute  +[a-z_]+ " $K/wg_$s.txt | grep -v gbuffer | cut -c1-112
done
tar czf $OUT/wg.tgz -C /tmp keep
echo "all: $(el) s"
