#!/usr/bin/env bash
# The second device call: after the tangent-plane step became one shared
# function (halfTexelRayHit), the ci and gpu-cpu matrices and the gpu
# matrix's fast half configurations rendered again, and their manifests
# brought back, so that check_digests.py can say whether every image is
# still one the card's class has approved (nothing changed on the GPU).
#   bash lab/2026-12-07_half_ray_depth/gpu_check.sh   (.gl and .bundle carried)
set -uo pipefail
cd "$(dirname "$0")/../.."
. scripts/gpu_env.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
nvidia-smi --query-gpu=name,driver_version --format=csv > "$OUT/check_gpu.csv" 2>&1; cat "$OUT/check_gpu.csv"
for m in ci gpu-cpu gpu; do
  flt=.; [ $m = gpu ] && flt='_fast/.*half/'
  .bundle/render.sh --matrix $m --filter "$flt" --out /tmp/render-$m > /tmp/render-$m.log 2>&1
  echo "render $m: rc $? ($(el) s)"; tail -1 /tmp/render-$m.log
  gzip -c /tmp/render-$m/manifest.json > "$OUT/check_manifest-$m.json.gz"
done
echo "all: $(el) s"
