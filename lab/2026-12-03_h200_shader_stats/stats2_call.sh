#!/usr/bin/env bash
# The driver's statistics on the H200: the backend test of them (no
# validation layer there), and every pass of the gpu matrix on Vulkan with
# the statistics in the render manifest.
set -uo pipefail
cd "$(dirname "$0")/.."
. scripts/gpu_env.sh
for f in .bundle/*.xz; do xz -dk "$f"; done; chmod +x .bundle/cavity_bench .bundle/cavity_render .bundle/test_backend
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
CAVITY_TEST_VALIDATION=0 LD_LIBRARY_PATH=.bundle/lib .bundle/test_backend > $OUT/test_backend.txt 2>&1
echo "test_backend: rc $? ($(el) s)"; grep -E "stats    \]|FAILED|Failure|PASSED|SKIPPED" $OUT/test_backend.txt | head -40
timeout 300 .bundle/render.sh --matrix gpu --filter '/vk/' --max-time 0.2 --out /tmp/stats > $OUT/render.log 2>&1
echo "render: rc $? ($(el) s)"
cp /tmp/stats/manifest.json $OUT/manifest.json
