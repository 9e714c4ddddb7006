#!/usr/bin/env bash
# Gates each subtle defect on the ci and gpu-cpu matrices (the configurations
# it touches), then scores every configuration it changed (score.py).
#   bash lab/2026-12-06_cpu_subtle_defects/run.sh OUT   (on the CPU renderers)
set -uo pipefail
cd "$(dirname "$0")/../.."
out="${1:?usage: run.sh OUT}"
here=lab/2026-12-06_cpu_subtle_defects
scripts/planted_defects.sh "$out/plants" --subtle > /dev/null
while read -r name file touches; do
  for m in ci gpu-cpu; do
    build/harness/cavity gate --matrix $m --filter "$touches" --retries 0 --quiet \
      --kernel-source "$file=$out/plants/$name.glsl" --out "$out/$name-$m" > /dev/null 2>&1
    echo "$name $m exit $?"
  done
done < "$out/plants/list.txt"
