#!/usr/bin/env bash
# The separable blur's shared tile against the texture path, and the tap
# loop written out, both APIs; then the gpu matrix's fast pipelines rendered
# to see whether any digest moved.
set -uo pipefail
cd "$(dirname "$0")/../.."
for f in .bundle/*.xz .bundle/lib/*.xz; do xz -d "$f"; done
chmod +x .bundle/cavity_bench .bundle/cavity .bundle/cavity_render
. scripts/gpu_env.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
mkdir -p /tmp/keep
# A: the kernel files of 40214b8, each cavity_main opening with
#   if (any(greaterThanEqual(pixel, frame.size))) return;
# (what its entry point did), in the ignored folder .old/blur_old
O=.old/blur_old
old=""
for f in include/blur_separable.glsl blur_separable_x.glsl blur_separable_y.glsl blur_separable_ssdo_x.glsl blur_separable_ssdo_y.glsl; do old="$old --kernel-source $f=$O/$f"; done
ab() {
  local name=$1 filter=$2 aargs=$3 bargs=$4
  smi_start /tmp/keep/$name.clocks.csv
  local extra=()
  [ -n "$aargs" ] && extra+=(--a-args="$aargs")
  [ -n "$bargs" ] && extra+=(--b-args="$bargs")
  .bundle/cavity.sh ab --a .bundle --b .bundle --rounds 4 --filter "$filter" \
    --bench-args='--max-time 0.3' "${extra[@]}" --out /tmp/keep/$name > /tmp/keep/$name.txt 2>&1
  echo "== $name: rc $? ($(el) s)"; grep -E "compute  +[a-z_]+ " /tmp/keep/$name.txt | grep -E " (blur_x|blur_y|ao|composite) " | cut -c1-110
  smi_stop
}
ab tiled '^corner/(alchemy_fast/n16/b4/(full|half)|ssdo_fast/n16/b4/full)/1920x1080/(gl|vk)/compute/' "$old" ""
ab written '^corner/alchemy_fast/n16/b4/(full|half)/1920x1080/(gl|vk)/compute/' "" "--kernel-source include/blur_separable.glsl=.old/blur_var/include/blur_separable.glsl"
tar czf $OUT/blur.tgz -C /tmp/keep .
echo "all: $(el) s"
