#!/usr/bin/env bash
# Writes a set of planted kernel defects, one edited copy of one kernel file
# each, for gating runs that must fail (docs/gate.md, "Gating a shader edit
# in one step"): DIR/<name>.glsl plus DIR/list.txt, a line per defect:
#   <name> <kernels/ file it replaces> <regex of the configurations it touches>
# Each is one small change of the kind a review misses; each edit is checked
# to have applied (the file differs from the original). With --subtle, the
# four systematic but slight errors the gate must fail clearly instead
# (docs/gate.md, "Subtle errors").
#   scripts/planted_defects.sh DIR [--subtle]
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:?usage: scripts/planted_defects.sh DIR [--subtle]}"
subtle="${2:-}"
if [ -n "$subtle" ] && [ "$subtle" != "--subtle" ]; then
  echo "planted_defects: second argument is '$subtle': only --subtle is allowed" >&2; exit 2
fi
mkdir -p "$out"
: > "$out/list.txt"
plant() {   # name, file under kernels/, configurations regex, sed expression
  local name=$1 file=$2 touches=$3 expr=$4
  sed "$expr" "kernels/$file" > "$out/$name.glsl"
  if cmp -s "kernels/$file" "$out/$name.glsl"; then echo "planted_defects: $name did not apply to $file" >&2; exit 1; fi
  echo "$name $file $touches" >> "$out/list.txt"
}
if [ -n "$subtle" ]; then
  # Positions rebuilt at the pixel's corner, not its centre: half a pixel
  # off (both builds of positionAt, the exact one and the fma one).
  plant half_pixel_shift include/pyramid.glsl '_fast/' \
    's|(vec2(pixel) + 0.5) \* frame.invSize|vec2(pixel) * frame.invSize|; s|(frame.invSize - 1.0) \* camera|(-1.0) * camera|'
  # The separable blur's background test reads the tap's AO, not its depth:
  # every fully occluded tap is dropped, in the tiled and texture paths.
  plant dropped_occluded_taps include/blur_separable.glsl '_fast/' \
    's|bool counts = !isBackground(tap.w);|bool counts = !isBackground(tileAo[i]);|; s|if (isBackground(tap.g)) continue;|if (isBackground(tap.r)) continue;|'
  # Alchemy takes one sample fewer than it divides by.
  plant wrong_sample_count ao/alchemy/ssao_alchemy.glsl '/alchemy/' \
    's|for (int i = 0; i < n; ++i) {|for (int i = 0; i < n - 1; ++i) {|'
  # The bilateral blur without its normal weight: AO bleeds across creases.
  plant missing_normal_weight include/blur_bilateral.glsl '/(alchemy|hemisphere|hemisphere_cosine|ssdo|ssdo_marched|sdf_[a-z]+)/' \
    's|float normalWeight = max(0.0, dot(N, Ni));|float normalWeight = 1.0;|'
  wc -l < "$out/list.txt" | xargs echo "planted_defects: subtle defects in $out/list.txt:"
  exit 0
fi
# The depth pyramid's pick with x and y swapped from level 3 down, in the
# one-dispatch build: coarse texels hold another pixel's depth, read only
# where samples land 64 px or more away.
plant pyramid_level3 include/pyramid_build.glsl '_fast/' \
  's|    if (pick != pixel >> (k - 1)) return false;|    if (k >= 3) pick = min(t * 2 + ivec2(t.x \& 1, t.y \& 1), levelSizeOf(k - 1) - 1);\n&|'
# alchemy_fast reads one pyramid level too coarse everywhere.
plant alchemy_fast_level ao/alchemy_fast/ssao_alchemy_fast.glsl '/alchemy_fast/' \
  's|int level = pyramidLevel(int(h), maxLevel);|int level = min(pyramidLevel(int(h), maxLevel) + 1, maxLevel);|'
# Alchemy's bias lowered by a tenth: a little more self-occlusion on flat ground.
plant alchemy_bias ao/alchemy/ssao_alchemy.glsl '/alchemy/' 's|dot(N, omega) - P.bias|dot(N, omega) - 0.9 * P.bias|'
# The composite's dither dropped: bands in the 8-bit gradients.
plant no_dither include/composite.glsl '/full/' 's|if (P.dither != 0) {|if (P.dither != 0 \&\& false) {|'
# The separable blur's Gaussian read one weight off (w[i+1] for w[i]).
plant blur_weight_shift include/blur_separable.glsl '_fast/' 's|return P.weights\[i >> 2\]\[i \& 3\];|return P.weights[(i + 1) >> 2][(i + 1) \& 3];|'
# The bilateral upsample's normal weight to the 4th power instead of the 8th.
plant upsample_normal include/upsample.glsl '/half/' 's|float normalWeight = cn \* cn;|float normalWeight = cn;|'
# hemisphere_fast's radius a twentieth short.
plant hemisphere_fast_radius ao/hemisphere_fast/ssao_hemisphere_fast.glsl '/hemisphere_fast/' 's|float R = P.radius;|float R = 0.95 * P.radius;|'
# ssdo_fast's bounce a tenth weak.
plant ssdo_bounce passes/ssdo_fast_indirect/ssdo_fast_indirect.glsl '/ssdo_fast/' 's|area \* P.bounce_strength / PI|area * 0.9 * P.bounce_strength / PI|'
wc -l < "$out/list.txt" | xargs echo "planted_defects: defects in $out/list.txt:"
