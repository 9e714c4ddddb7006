#!/usr/bin/env bash
# The four subtle defects the gate must fail clearly (docs/gate.md, "Subtle
# errors"), each one edited copy of one kernel file, with the configurations
# it touches:
#   DIR/<name>.glsl and DIR/list.txt: <name> <kernels/ file> <regex>
#   bash lab/2026-12-06_cpu_subtle_defects/plant.sh DIR
set -euo pipefail
cd "$(dirname "$0")/../.."
out="${1:?usage: plant.sh DIR}"
mkdir -p "$out"
: > "$out/list.txt"
plant() {   # name, file under kernels/, configurations regex, sed expression
  local name=$1 file=$2 touches=$3 expr=$4
  sed "$expr" "kernels/$file" > "$out/$name.glsl"
  if cmp -s "kernels/$file" "$out/$name.glsl"; then echo "plant.sh: $name did not apply to $file" >&2; exit 1; fi
  echo "$name $file $touches" >> "$out/list.txt"
}
# Positions rebuilt at the pixel's corner, not its centre: half a pixel off
# (both builds of positionAt: the exact one and the fma one).
plant half_pixel_shift include/pyramid.glsl '_fast/' \
  's|(vec2(pixel) + 0.5) \* frame.invSize|vec2(pixel) * frame.invSize|; s|(frame.invSize - 1.0) \* camera|(-1.0) * camera|'
# The separable blur's background test reads the tap's AO, not its depth:
# every fully occluded tap (AO 0) is dropped, in the tiled and texture paths.
plant dropped_occluded_taps include/blur_separable.glsl '_fast/' \
  's|bool counts = !isBackground(tap.w);|bool counts = !isBackground(tileAo[i]);|; s|if (isBackground(tap.g)) continue;|if (isBackground(tap.r)) continue;|'
# Alchemy takes one sample fewer than it divides by: n - 1 taps weighed as n.
plant wrong_sample_count ao/alchemy/ssao_alchemy.glsl '/alchemy/' \
  's|for (int i = 0; i < n; ++i) {|for (int i = 0; i < n - 1; ++i) {|'
# The bilateral blur without its normal weight: AO bleeds across creases.
plant missing_normal_weight include/blur_bilateral.glsl '/(alchemy|hemisphere|hemisphere_cosine|ssdo|ssdo_marched|sdf_[a-z]+)/' \
  's|float normalWeight = max(0.0, dot(N, Ni));|float normalWeight = 1.0;|'
wc -l < "$out/list.txt" | xargs echo "plant.sh: defects in $out/list.txt:"
