#!/usr/bin/env bash
# Interleaved A/B on the GPU machine (docs/comparing.md, "Two builds
# interleaved"): `cavity ab` with B the bundle's cavity_bench given a planted
# slowdown (PLANT.json, from lab/scripts/gpu_sensitivity.sh), then A against A,
# each with the clocks sampled beside it. Every round's JSON comes back in
# ab.tgz, so that the rounds needed to call the change can be counted here
# (lab/scripts/ab_rounds.py ab1, and aa).
#   lab/scripts/gpu_ab.sh PLANT.json [ROUNDS (8)] [MAX_TIME_S (0.25)] [FILTER]
set -uo pipefail
cd "$(dirname "$0")/.."
. scripts/gpu_env.sh
plant="$(realpath "${1:?PLANT.json}")"
rounds="${2:-8}"
maxt="${3:-0.25}"
filter="${4:-^corner/(alchemy|alchemy_fast|hemisphere|hemisphere_fast)/n16/b4/(full|half)/1920x1080/(gl|vk)/compute/}"
# B: the same binary, its AO kernel source given the planted FMAs.
cat > .bundle/cavity_bench_planted <<EOF
#!/usr/bin/env bash
exec "\$(dirname "\$0")/cavity_bench" --plant-file "$plant" "\$@"
EOF
chmod +x .bundle/cavity_bench_planted
ab() {   # name, B binary
  local name=$1 b=$2 t0
  t0=$(date +%s.%N)
  smi_start "$OUT/$name.clocks.csv"
  .bundle/cavity.sh ab --a .bundle/cavity_bench --b "$b" --rounds "$rounds" --filter "$filter" \
    --bench-args="--sweep gpu --max-time $maxt" --out "$OUT/$name" > "$OUT/$name.txt" 2> "$OUT/$name.err"
  local rc=$?
  smi_stop
  echo "== $name: exit $rc, $(python3 -c "import time; print(round(time.time() - $t0, 1))") s"
  tail -3 "$OUT/$name.txt"
}
ab ab1 .bundle/cavity_bench_planted
ab aa .bundle/cavity_bench
cd "$OUT" && tar czf ab.tgz ab1 aa ./*.csv ./*.txt ./*.err && rm -rf ab1 aa ./*.csv ./*.txt ./*.err
ls -la "$OUT"
