#!/usr/bin/env bash
# The fast kernels' MAE against the ray-traced ground truth at half
# resolution, three scenes, n16 and n32, three sizes, with the cavity binary
# given (the build before the change, then this one), on this machine's
# lavapipe:
#   bash lab/2026-12-07_half_ray_depth/quality.sh CAVITY NAME   (writes quality_NAME_WxH.json)
set -euo pipefail
cavity=$1 name=$2
here=$(cd "$(dirname "$0")" && pwd)
for res in 160x90 320x180 640x360; do
  "$cavity" quality --scene corner,slats,open --kernel alchemy,alchemy_fast,hemisphere_fast --samples 16,32 \
    --resolution half --res "$res" --out "/tmp/half_ray_quality_${name}_$res" > /dev/null 2>&1
  cp "/tmp/half_ray_quality_${name}_$res/quality.json" "$here/quality_${name}_$res.json"
  echo "$name $res done"
done
