#!/usr/bin/env bash
# Ingests what scripts/gpu_history.sh brought back (DIR: <commit>.json per
# build, commits.tsv) into DB with each commit's real id, parent and date,
# then lists the change points and draws the chart.
#   scripts/history_ingest.sh DIR DB [OUT (DIR/chart)] [cavity history alerts flags...]
set -euo pipefail
cd "$(dirname "$0")/.."
dir="${1:?DIR DB}"
db="${2:?DIR DB}"
out="${3:-$dir/chart}"
shift $(( $# < 3 ? $# : 3 ))
cavity="${CAVITY:-build/harness/cavity}"
[ -f "$dir/commits.tsv" ] || { echo "history_ingest: $dir/commits.tsv: missing (scripts/gpu_history.sh writes it)" >&2; exit 2; }
# Split on each tab by hand: `read` with IFS=$'\t' folds two tabs into one,
# and a first commit's parent field is empty.
while IFS= read -r line; do
  commit=${line%%$'\t'*}; rest=${line#*$'\t'}
  parent=${rest%%$'\t'*}; rest=${rest#*$'\t'}
  date=${rest%%$'\t'*}; subject=${rest#*$'\t'}
  f="$dir/${commit:0:12}.json"
  [ -f "$f" ] || { echo "history_ingest: $f: missing for $commit ($subject)" >&2; exit 2; }
  "$cavity" history ingest --db "$db" --commit "$commit" ${parent:+--parent "$parent"} --date "$date" \
    --branch main "$f"
done < "$dir/commits.tsv"
"$cavity" history show --db "$db" > "$dir/show.txt"
"$cavity" history alerts --db "$db" --json "$dir/alerts.json" --bisect "$@" | tee "$dir/alerts.txt"
"$cavity" history chart --db "$db" --out "$out"
