#!/usr/bin/env bash
# The gate's planted-bug set (tests/test_gate.cpp, the source edits) rendered
# on the GPU machine with cavity_render --kernel-source, one render folder per
# defect, packed into $OUT/planted.tar. Judge each here:
#   for d in out/planted/*/; do build/harness/cavity gate judge $d --out out/judge-$(basename $d); done
set -uo pipefail
cd "$(dirname "$0")/../.."
. scripts/gpu_env.sh
work=/tmp/cavity-planted
rm -rf "$work"; mkdir -p "$work"
# name | kernel file | text | replacement | configurations
while IFS='|' read -r name file find replace filter; do
  python3 - "$file" "$find" "$replace" "$work/$name.glsl" <<'PY' || exit 1
import sys
src, find, replace, out = open("kernels/" + sys.argv[1]).read(), sys.argv[2], sys.argv[3], sys.argv[4]
if find not in src:
    sys.exit(f"gpu_planted: '{find}' not in kernels/{sys.argv[1]}: the defect would not be planted")
open(out, "w").write(src.replace(find, replace, 1))
PY
  .bundle/render.sh --matrix ci --filter "$filter" --max-noise 0 --kernel-source "$file=$work/$name.glsl" \
    --out "$work/planted/$name" > "$work/$name.log" 2>&1
  echo "$name: rc=$? $(tail -1 "$work/$name.log")"
done <<'LIST'
bias_sign_flipped|ssao_alchemy.glsl|- P.bias|+ P.bias|^corner/alchemy/n16/b4/full/160x90/(gl|vk)/compute$
sample_count_off_by_one|ssao_alchemy.glsl|int n = P.samples;|int n = P.samples + 1;|^corner/alchemy/n16/b4/full/160x90/(gl|vk)/compute$
near_clamp_c_eq_R|ssao_alchemy.glsl|float c = 0.1 * R;|float c = R;|^corner/alchemy/n16/b4/full/160x90/(gl|vk)/compute$
range_check_removed|ssao_hemisphere.glsl|if (P.range_check != 0) rangeWeight = smoothstep(0.0, 1.0, P.radius / max(abs(p.z - q.z), 1e-6));||^corner/hemisphere/n16/b4/full/160x90/(gl|vk)/compute$
upsample_offset_one_texel|include/upsample.glsl|ivec2 base = ivec2(floor(c));|ivec2 base = ivec2(floor(c)) + ivec2(1, 0);|^corner/alchemy/n16/b4/half/160x90/(gl|vk)/compute$
LIST
tar -C "$work" -cf "$OUT/planted.tar" planted
ls -la "$OUT"
