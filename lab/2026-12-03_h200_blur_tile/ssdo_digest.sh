#!/usr/bin/env bash
# ssdo_fast's gpu-matrix compute configurations rendered with the committed direct
# and bounce passes (given as --kernel-source over the bundle of fd45e48)
# and judged there by approved digest.
set -uo pipefail
cd "$(dirname "$0")/../.."
for f in .bundle/*.xz .bundle/lib/*.xz; do xz -d "$f"; done
chmod +x .bundle/cavity_render .bundle/cavity
. scripts/gpu_env.sh
.bundle/render.sh --matrix gpu --filter 'ssdo_fast/.*/compute$' --out /tmp/r \
  --kernel-source ssdo_fast_direct.glsl=kernels/ssdo_fast_direct.glsl --kernel-source ssdo_fast_indirect.glsl=kernels/ssdo_fast_indirect.glsl > /tmp/render.txt 2>&1
echo "render rc $?; image files: $(find /tmp/r -name '*.f32z' | wc -l)"
.bundle/cavity.sh gate judge /tmp/r --out /tmp/g --quiet 2>&1 | head -8
