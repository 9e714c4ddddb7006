#!/usr/bin/env bash
# The H200's approved digests, FNV-1a until now, rewritten as SHA-256 the way
# a user migrates: render the gpu matrix on the H200 (every image: none of
# its SHA-256 digests is approved yet), then `cavity baselines
# migrate-digests --from` that render. approvals.json comes back; the store
# objects stay there (an approved digest passes without its pixels).
#   bash lab/2026-12-06_h200_sha256/call1.sh   (on the GPU machine, .gl and .bundle carried)
set -uo pipefail
cd "$(dirname "$0")/../.."
. scripts/gpu_env.sh
start=$(date +%s)
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.max.sm --format=csv > "$OUT/gpu.csv" 2>&1
.bundle/render.sh --matrix gpu --out /tmp/render > "$OUT/render.log" 2>&1
echo "render rc=$? ($(( $(date +%s) - start )) s)"
tail -3 "$OUT/render.log"
.bundle/cavity.sh baselines migrate-digests --baselines baselines --store /tmp/store --from /tmp/render \
  --keep-unmigrated > "$OUT/migrate.log" 2>&1
echo "migrate rc=$?"
tail -5 "$OUT/migrate.log"
cp baselines/approvals.json "$OUT/approvals.json"
# The migrated set judged as the gate would: the render folder against it.
.bundle/cavity.sh gate judge /tmp/render --baselines baselines --out /tmp/gate > "$OUT/judge.log" 2>&1
echo "judge rc=$?"
tail -4 "$OUT/judge.log"
echo "done ($(( $(date +%s) - start )) s)"
