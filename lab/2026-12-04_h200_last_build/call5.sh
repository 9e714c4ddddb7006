#!/usr/bin/env bash
# The whole gpu matrix (100 configurations) rendered with the session's last
# build and judged by digest against the approved ones.
set -uo pipefail
. scripts/gpu_env.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
K=/tmp/keep; rm -rf $K; mkdir -p $K
work=/tmp/refs; rm -rf $work; mkdir -p $work; cp -r baselines $work/base
.bundle/render.sh --matrix gpu --baselines $work/base --out $work/r > $K/render.txt 2>&1
echo "== render: rc $? ($(el) s)"; tail -1 $K/render.txt
.bundle/cavity.sh gate judge $work/r --baselines $work/base --out $work/g --quiet > $K/judge.md 2>&1
echo "== judge: rc $?"; head -3 $K/judge.md
tar czf $OUT/call5.tgz -C /tmp keep; echo "all: $(el) s"
