#!/usr/bin/env bash
# The downsample back to picking on the positions (call.sh found it 8%
# slower comparing the linear depth), still writing the half-resolution
# depth the half pyramid reads: cavity ab, A the build before the linear
# depth (.bundle2), B this one, 4 rounds, alchemy_fast full and half; then
# the gpu matrix's half-resolution pipelines rendered and judged by digest.
set -uo pipefail
cd "$(dirname "$0")/../.."
. scripts/gpu_env.sh
.bundle2/unpack.sh   # the wrappers unpack on first use; cavity ab runs its binary
[ "${SKIP_RENDER:-0}" = 1 ] && RENDER=0 || RENDER=1
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
K=/tmp/keep; rm -rf $K; mkdir -p $K
smi_start $K/ab.clocks.csv
.bundle/cavity.sh ab --a .bundle2 --b .bundle --rounds 4 \
  --filter '^corner/alchemy_fast/n16/b4/((fused_tail=1/)?half|full)/1920x1080/(gl|vk)/compute/' \
  --bench-args='--sweep gpu --max-time 0.3' --out $K/ab > $K/ab.txt 2>&1
echo "== ab: rc $? ($(el) s)"; smi_stop
grep -E "compute +(pipeline|pyramid|downsample) " $K/ab.txt | cut -c1-125
[ "$RENDER" = 1 ] || { tar czf $OUT/call2.tgz -C /tmp keep; exit 0; }
work=/tmp/refs; rm -rf $work; mkdir -p $work; cp -r baselines $work/base
.bundle/render.sh --matrix gpu --filter '/half/' --baselines $work/base --out $work/r0 > $K/render0.txt 2>&1
echo "== render: rc $? ($(el) s); image files: $(find $work/r0 -name '*.f32z' | wc -l)"
.bundle/cavity.sh gate judge $work/r0 --baselines $work/base --out $work/g0 --quiet > $K/judge.md 2>&1
echo "== judge: rc $? ($(el) s)"; head -3 $K/judge.md; cp $work/g0/gate.json $K/judge.json
tar czf $OUT/call2.tgz -C /tmp keep; echo "all: $(el) s"
