#!/usr/bin/env bash
# Workgroup shapes for the fixed full-resolution passes (the pyramid, the
# composite, the blurs), each cavity ab's B against B, B's processes with
# CAVITY_WORKGROUP=WxH (every pass takes that shape; the AO's rows are not
# what this measures), 4 rounds, alchemy_fast n16 b4 full.
set -uo pipefail
. scripts/gpu_env.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
K=/tmp/keep; rm -rf $K; mkdir -p $K
filter='^corner/alchemy_fast/n16/b4/full/1920x1080/(gl|vk)/compute/'
.bundle/unpack.sh
for shape in 32x8 32x16 32x32 64x4; do
  W=/tmp/wg_$shape; rm -rf $W; mkdir -p $W; ln -s "$PWD/.bundle/lib" $W/lib
  printf '#!/usr/bin/env bash\nexport CAVITY_WORKGROUP=%s\nexec %s "$@"\n' $shape "$PWD/.bundle/cavity_bench" > $W/cavity_bench
  chmod +x $W/cavity_bench
  smi_start $K/ab_$shape.clocks.csv
  .bundle/cavity.sh ab --a .bundle --b $W/cavity_bench --rounds 4 --filter "$filter" \
    --bench-args='--sweep gpu --max-time 0.3' --out $K/ab_$shape > $K/ab_$shape.txt 2>&1
  echo "== ab $shape: rc $? ($(el) s)"; smi_stop
  grep -E "compute +(pyramid|composite|blur_x|blur_y) " $K/ab_$shape.txt | cut -c1-125
done
tar czf $OUT/call2.tgz -C /tmp keep; echo "all: $(el) s"
