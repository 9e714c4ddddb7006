#!/usr/bin/env bash
# Measures the builds of scripts/history_bundle.sh interleaved on the GPU
# machine, as Pinpoint alternates two: ROUNDS rounds, each running every
# build once in a shuffled order (one cavity_bench process each, its
# configurations shuffled too), so drift over the call falls on every commit
# alike. Each build's rounds are merged into <commit>.json, one repetition a
# round, and come back in history.tgz with commits.tsv and the clocks; ingest
# them here with scripts/history_ingest.sh.
#   scripts/gpu_history.sh BUNDLE.tar.xz [ROUNDS (5)] [MAX_TIME_S (0.25)] [FILTER]
set -uo pipefail
cd "$(dirname "$0")/.."
. scripts/gpu_env.sh
bundle="${1:?BUNDLE.tar.xz}"
rounds="${2:-5}"
maxt="${3:-0.25}"
filter="${4:-^corner/(alchemy_fast|hemisphere_fast)/n16/b4/(full|half)/1920x1080/(gl|vk)/compute/}"
work=$(mktemp -d)
tar -C "$work" -xJf "$bundle"
h="$work/history"
export LD_LIBRARY_PATH="$h/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
mkdir -p "$OUT/runs"
start=$(date +%s)
smi_start "$OUT/clocks.csv"
for r in $(seq 0 $((rounds - 1))); do
  for b in $(ls "$h"/bench_* | shuf); do
    c=${b##*/bench_}
    "$b" --sweep gpu --benchmark_filter="$filter" --benchmark_repetitions=1 \
      --benchmark_enable_random_interleaving=true --max-time "$maxt" \
      --benchmark_out="$OUT/runs/${c}_$r.json" --benchmark_out_format=json > "$OUT/runs/${c}_$r.log" 2>&1 ||
      echo "gpu_history: $c round $r failed: $(tail -1 "$OUT/runs/${c}_$r.log")"
  done
  echo "gpu_history: round $((r + 1))/$rounds done ($(( $(date +%s) - start )) s)"
done
smi_stop
# One file per commit: the rounds' iteration entries, repetition k = round k.
python3 - "$OUT/runs" "$OUT" <<'PY'
import glob, json, os, re, sys
sys.path.insert(0, "scripts/charts")
import cavity_json   # scripts/charts/cavity_json.py
runs, out = sys.argv[1], sys.argv[2]
by = {}
for f in sorted(glob.glob(os.path.join(runs, "*_*.json"))):
    c, r = re.match(r"(.+)_(\d+)\.json$", os.path.basename(f)).groups()
    by.setdefault(c, []).append((int(r), f))
for c, files in by.items():
    merged = cavity_json.merge_rounds([f for _, f in sorted(files)])
    json.dump(merged, open(os.path.join(out, c + ".json"), "w"))
PY
cp "$h/commits.tsv" "$OUT/"
echo "gpu_history: done ($(( $(date +%s) - start )) s)"
cd "$OUT" && tar czf history.tgz ./*.json commits.tsv clocks.csv runs && rm -rf ./*.json clocks.csv runs commits.tsv
ls -la "$OUT"
