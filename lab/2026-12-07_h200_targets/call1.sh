#!/usr/bin/env bash
# The round-three targets (study 2026-12-06_gpu_round3, call2.sh) on the
# H200 they were set on, and only there: on any other card it stops at
# once, so that a call that got an H100 again costs its start alone.
#   bash lab/2026-12-07_h200_targets/call1.sh   (.gl and .bundle carried)
set -uo pipefail
cd "$(dirname "$0")/../.."
name=$(nvidia-smi --query-gpu=name --format=csv,noheader 2>&1 | head -1)
echo "card: $name"
case "$name" in
  *H200*) exec bash lab/2026-12-06_gpu_round3/call2.sh ;;
  *) echo "not an H200: nothing measured"; exit 3 ;;
esac
