#!/usr/bin/env bash
# The last call of the session: the statistics test again (the query
# rewritten), an edited kernel timed with cavity ab --b-args (one phase for
# every pixel, B only), and the fast kernels against their targets with 10
# interleaved repetitions (lab/scripts/gpu_kernels2.sh 10 0.3).
set -uo pipefail
cd "$(dirname "$0")/.."
for f in .bundle/*.xz; do xz -dk "$f"; done
chmod +x .bundle/cavity_bench .bundle/cavity_render .bundle/cavity .bundle/test_backend
. scripts/gpu_env.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
CAVITY_TEST_VALIDATION=0 LD_LIBRARY_PATH=.bundle/lib .bundle/test_backend --gtest_filter='*Statistic*:*MissingBarrier*' > $OUT/test_backend.txt 2>&1
echo "test_backend: rc $? ($(el) s)"; grep -E "stats    \]|PASSED|FAILED|SKIPPED" $OUT/test_backend.txt | head -20
smi_start $OUT/ab.clocks.csv
.bundle/cavity.sh ab --a .bundle --b .bundle --rounds 4 --filter '^corner/alchemy_fast/n16/b4/full/1920x1080/(gl|vk)/compute/' \
  --bench-args='--max-time 0.3' --b-args='--kernel-source ssao_alchemy_fast.glsl=.old/coh/ssao_alchemy_fast.glsl' --out /tmp/ab > $OUT/ab.txt 2>&1
echo "cavity ab: rc $? ($(el) s)"; tail -12 $OUT/ab.txt
smi_stop
tar czf $OUT/ab.tgz -C /tmp ab
bash lab/scripts/gpu_kernels2.sh 10 0.3 2>&1 | tail -14
echo "all: $(el) s"
