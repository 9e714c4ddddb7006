#!/usr/bin/env bash
# Three edits with the same images (checked on llvmpipe and lavapipe), each
# B against B+edit, 4 rounds:
#  int:     pyramid_int.glsl: the level as min(findMSB(h | 8) - 3, max) and the
#           texel as min(s, size - 2^l) >> l (a clamp and a shift fewer);
#  written: hemisphere_written_out.glsl: hemisphere_fast's points written out
#           for GL (tried before the stored sources: +1.4% there);
#  both.
set -uo pipefail
. scripts/gpu_env.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
K=/tmp/keep; rm -rf $K; mkdir -p $K
int="--kernel-source include/pyramid.glsl=$PWD/.old/v/pyramid_int.glsl"
wo="--kernel-source ssao_hemisphere_fast.glsl=$PWD/.old/v/hemisphere_written_out.glsl"
fa='^corner/(alchemy_fast|hemisphere_fast)/n(16|32)/b4/full/1920x1080/(gl|vk)/compute/'
fh='^corner/hemisphere_fast/n(16|32)/b4/full/1920x1080/(gl|vk)/compute/'
smi_start $K/clocks.csv
for v in int written both; do
  case $v in int) f=$fa; args=$int;; written) f=$fh; args=$wo;; both) f=$fh; args="$int $wo";; esac
  .bundle/cavity.sh ab --a .bundle --b .bundle --rounds 4 --filter "$f" \
    --bench-args='--sweep gpu --max-time 0.3' --b-args="$args" --out $K/$v > $K/$v.txt 2>&1
  echo "== $v: rc $? ($(el) s)"
  grep -E "compute +(pipeline|ao) " $K/$v.txt | cut -c1-125
done
smi_stop
tar czf $OUT/call4.tgz -C /tmp keep; echo "all: $(el) s"
