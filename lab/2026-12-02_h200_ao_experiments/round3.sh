#!/usr/bin/env bash
# Round 3: the spiral direction by a rotation recurrence (no uniform table) against the committed table.
set -uo pipefail
cd "$(dirname "$0")/.."
. scripts/gpu_env.sh
work=/tmp/exp3; rm -rf $work; mkdir -p $work
declare -A V
V[table]=""
V[recurrence]="--kernel-source ssao_alchemy_fast.glsl=.exp/ao3_recurrence.glsl"
smi_start $work/clocks.csv
for round in 1 2 3; do
  for v in table recurrence; do
    d=$work/$v.r$round
    timeout 120 .bundle/render.sh --matrix gpu --filter '^corner/(alchemy|alchemy_fast)/n16/b4/full/1920x1080/(gl|vk)/compute$' \
      --max-noise 0.5 --max-time 1 ${V[$v]} --out $d > $d.log 2>&1
    echo "$v r$round rc $? $(tail -1 $d.log)"
    find $d -type f ! -name manifest.json -delete
  done
done
smi_stop
tar -C $work -czf $OUT/exp3.tgz .
