#!/usr/bin/env bash
# The second session's runs: each subtle defect rendered (cavity_render, so
# the pixels come back as f32z), clean renders of ci and gpu-cpu with no
# approvals (every image written), the candidates scored (pairs.py, then
# separation.py), and each defect gated as a clean clone would (no image
# store: changed images against the stored baselines) under BASELINES's
# manifest.
#   bash lab/2026-12-06_cpu_subtle_defects/tier.sh OUT BASELINES [H100_RENDERS]
set -uo pipefail
cd "$(dirname "$0")/../.."
out="${1:?usage: tier.sh OUT BASELINES [H100_RENDERS]}"; base="${2:?}"; h100="${3:-}"
here=lab/2026-12-06_cpu_subtle_defects
scripts/planted_defects.sh "$out/plants" --subtle > /dev/null
mkdir -p "$out/noapprovals"
cp -r "$base"/{matrices.json,manifest.json,budgets.json,expectations,images} "$out/noapprovals/"
echo '{"schema": "cavity.approvals/1", "approvals": []}' > "$out/noapprovals/approvals.json"
for m in ci gpu-cpu; do
  build/render/cavity_render --matrix $m --baselines "$out/noapprovals" --out "$out/clean-$m" > /dev/null 2>&1
done
while read -r name file touches; do
  for m in ci gpu-cpu; do
    build/render/cavity_render --matrix $m --filter "$touches" --kernel-source "$file=$out/plants/$name.glsl" \
      --out "$out/render-$name-$m" > /dev/null 2>&1
    python3 $here/pairs.py "$out/render-$name-$m" "$out/clean-$m" "$name-$m" >> "$out/defects.jsonl"
    CAVITY_STORE=/nonexistent build/harness/cavity gate --matrix $m --filter "$touches" --retries 0 --quiet \
      --baselines "$base" --kernel-source "$file=$out/plants/$name.glsl" --out "$out/gate/$name-$m" > /dev/null 2>&1
    echo "$name $m gate exit $?"
  done
done < "$out/plants/list.txt"
for m in ci gpu-cpu; do
  python3 $here/pairs.py "$out/clean-$m" "$out/clean-$m" "cpuapi-$m" glcompute >> "$out/noise_cpu.jsonl"
  [ -n "$h100" ] && python3 $here/pairs.py "$h100/r_$m" "$out/clean-$m" "h100-$m" >> "$out/noise_h100.jsonl"
done
python3 $here/separation.py "$out"
python3 -c "import sys; sys.path.insert(0, '$here'); import score; score.failing_table('$out/gate', tile=False)"
