#!/usr/bin/env bash
# The driver's statistics of every pipeline, then the sample loops with
# [[dont_unroll]] against the committed ones (ROUNDS shuffled rounds, each
# its own cavity_render process), on the H200.
#   .old/stats_call.sh ROUNDS       (carry .gl .bundle .old)
set -uo pipefail
cd "$(dirname "$0")/.."
. scripts/gpu_env.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
for f in .bundle/*.xz; do xz -dk "$f"; done; chmod +x .bundle/cavity_bench .bundle/cavity_render .bundle/test_backend; LD_LIBRARY_PATH=.bundle/lib .bundle/test_backend --gtest_filter='*Statistic*' > $OUT/stats_test.txt 2>&1
echo "test_backend statistics: rc $? ($(el) s)"; grep -E "stats    \]|OK|FAILED|Failure" $OUT/stats_test.txt | head -40
.bundle/run.sh --sweep gpu --benchmark_filter='^corner/[a-z_]+/n(16|32)/b4/([a-z_]+=[0-9]+/)?(full|half)/1920x1080/vk/compute/' \
  --benchmark_repetitions=1 --max-time 0.05 --benchmark_out=$OUT/regs.json --benchmark_out_format=json > $OUT/regs.txt 2> $OUT/regs.err
echo "cavity_bench: rc $? ($(el) s)"
work=$(mktemp -d)
smi_start $work/clocks.csv
for r in $(seq 1 "$1"); do
  for v in $(printf 'new\ndu\n' | shuf); do
    for k in alchemy_fast hemisphere_fast; do
      src=(); [ $v = du ] && src=(--kernel-source ssao_$k.glsl=.old/du/ssao_$k.glsl)
      d=$work/$v.$k.r$r
      timeout 120 .bundle/render.sh --matrix ab --baselines .old/base --filter "^corner/$k/" --max-noise 0.5 --max-time 1 "${src[@]}" --out $d > $d.log 2>&1
      echo "$v $k r$r rc $? ($(el) s)"
      find $d -type f ! -name manifest.json -delete
    done
  done
done
smi_stop
tar -C $work -czf $OUT/stats_call.tgz .
