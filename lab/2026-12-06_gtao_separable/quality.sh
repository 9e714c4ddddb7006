#!/usr/bin/env bash
# GTAO's error against the ray-traced truth after the blur, with the 2D
# bilateral blur it had (the probe package of 2026-12-05_gpu_gtao holds the
# separable one) and with the separable one: lavapipe, n16, b4, R = 0.5.
#   bash lab/2026-12-06_gtao_separable/quality.sh > lab/2026-12-06_gtao_separable/quality.txt
# Run from the commit before the switch (gtao = bilateral, gtao_separable = separable).
cd "$(dirname "$0")/../.."
for a in "--res 160x90" "--res 320x180" "--res 640x360" "--res 320x180 --resolution half"; do
  echo "== $a"
  build/harness/cavity quality --kernels lab/2026-12-05_gpu_gtao/probe_separable --kernel gtao,gtao_separable,alchemy_fast \
    --samples 16 --blur 4 $a 2>&1 | grep -E "^(scene|corner|slats)"
done
