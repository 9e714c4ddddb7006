#!/usr/bin/env bash
# Written-out and [[unroll]] loops against the kernels as they are, both APIs,
# one binary, B's kernel files through --kernel-source (cavity ab).
set -uo pipefail
cd "$(dirname "$0")/.."
for f in .bundle/*.xz .bundle/lib/*.xz; do xz -d "$f"; done
chmod +x .bundle/cavity_bench .bundle/cavity
. scripts/gpu_env.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
n16='^corner/(alchemy|hemisphere)_fast/n16/b4/(fused_tail=1/)?(full|half)/1920x1080/(gl|vk)/compute/'
n32='^corner/alchemy_fast/n32/b4/full/1920x1080/(gl|vk)/compute/'
ab() {
  local name=$1 filter=$2; shift 2
  local bargs=""
  for s in "$@"; do bargs="$bargs --kernel-source $s"; done
  smi_start $OUT/$name.clocks.csv
  .bundle/cavity.sh ab --a .bundle --b .bundle --rounds 4 --filter "$filter" \
    --bench-args='--max-time 0.3' --b-args="$bargs" --out /tmp/$name > $OUT/$name.txt 2>&1
  echo "== $name: rc $? ($(el) s)"; grep -E "compute  +[a-z_]+ " $OUT/$name.txt | grep -vE " (gbuffer|blur_x|blur_y|composite|downsample) " | cut -c1-100
  smi_stop
  mkdir -p /tmp/keep && cp $OUT/$name.txt $OUT/$name.clocks.csv /tmp/keep/ && rm -f $OUT/$name.txt $OUT/$name.clocks.csv
  cp -r /tmp/$name /tmp/keep/
}
V=.old/v
ab chain "$n16" depth_pyramid_single.glsl=$V/pyr_chain.glsl include/upsample.glsl=$V/up_chain.glsl \
  ssao_alchemy_fast.glsl=$V/ao16.glsl ssao_hemisphere_fast.glsl=$V/hemi16.glsl
ab unroll "$n16" depth_pyramid_single.glsl=$V/pyr_unroll.glsl include/upsample.glsl=$V/up_unroll.glsl \
  ssao_alchemy_fast.glsl=$V/ao16u.glsl ssao_hemisphere_fast.glsl=$V/hemi16u.glsl
ab nosrc "^corner/(alchemy|hemisphere)_fast/n16/b4/full/1920x1080/(gl|vk)/compute/" ssao_alchemy_fast.glsl=$V/ao_nosrc.glsl include/pyramid.glsl=$V/pyramid_nosrc.glsl
echo "all: $(el) s"
tar czf $OUT/all.tgz -C /tmp keep
