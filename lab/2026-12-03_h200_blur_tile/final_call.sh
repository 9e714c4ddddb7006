#!/usr/bin/env bash
# 0. The upsample's tile against the texture path, interleaved (cavity ab).
# 1. The gpu matrix's fast pipelines rendered: which digests moved against
#    baselines/approvals.json; those approved for the H200 (as
#    gpu_references.sh does, filtered), then rendered and judged again.
# 2. alchemy_fast on GL with its kernel as it was before the GL form that
#    writes the samples out (fd04745's ssao_alchemy_fast.glsl, in
#    .old/alchemy_pre11.glsl), to see whether that is what moved GL's digests.
# 3. The targets: 10 interleaved repetitions, the clocks beside them.
set -uo pipefail
cd "$(dirname "$0")/../.."
for f in .bundle/*.xz .bundle/lib/*.xz; do xz -d "$f"; done
chmod +x .bundle/cavity_bench .bundle/cavity .bundle/cavity_render
. scripts/gpu_env.sh
start=$(date +%s); el() { echo $(( $(date +%s) - start )); }
K=/tmp/keep; mkdir -p $K
# A of the upsample: the files of 8a048f9 with the same guard, in .old/up_old
U=.old/up_old
smi_start $K/up_ab.clocks.csv
.bundle/cavity.sh ab --a .bundle --b .bundle --rounds 4 \
  --filter '^corner/(alchemy_fast|hemisphere_fast)/n16/b4/(fused_tail=1/)?half/1920x1080/(gl|vk)/compute/' \
  --bench-args='--sweep gpu --max-time 0.3' --a-args="--kernel-source include/upsample.glsl=$U/include/upsample.glsl --kernel-source upsample_bilateral.glsl=$U/upsample_bilateral.glsl --kernel-source upsample_composite.glsl=$U/upsample_composite.glsl" \
  --out $K/up_ab > $K/up_ab.txt 2>&1
echo "== upsample ab: rc $? ($(el) s)"; smi_stop
grep -E "compute  +(upsample|upsample_composite|ao|blur_x) " $K/up_ab.txt | cut -c1-110
work=/tmp/refs; rm -rf $work; mkdir -p $work; cp -r baselines $work/base
smi_start $K/render.clocks.csv
.bundle/render.sh --matrix gpu --filter '_fast/' --baselines $work/base --out $work/r0 > $K/render0.txt 2>&1
echo "== render 0: rc $? ($(el) s); image files: $(find $work/r0 -name '*.f32z' | wc -l)"
find $work/r0 -name '*.f32z' | sed "s|$work/r0/images/||"
mkdir -p $K/moved && (cd $work/r0 && find . -name '*.f32z' | tar cf - -T - | tar xf - -C $K/moved) && cp $work/r0/manifest.json $K/manifest0.json
# the VK images of the configurations whose GL images moved, for the diff here
nb=$work/noapprovals; mkdir -p $nb; cp baselines/matrices.json baselines/manifest.json baselines/budgets.json $nb/
.bundle/render.sh --matrix gpu --filter 'corner/alchemy_fast/.*/vk/' --baselines $nb --out $work/rvk > $K/rvk.txt 2>&1
echo "== vk images: rc $? ($(el) s)"
mkdir -p $K/vk && (cd $work/rvk && find . -name '*.f32z' | tar cf - -T - | tar xf - -C $K/vk)
.bundle/render.sh --matrix gpu --filter 'corner/alchemy_fast/.*/gl/' --baselines $work/base --out $work/rold \
  --kernel-source ssao_alchemy_fast.glsl=.old/alchemy_pre11.glsl > $K/rold.txt 2>&1
echo "== gl, kernel before the written-out form: rc $? ($(el) s); image files: $(find $work/rold -name '*.f32z' | wc -l)"
cp $work/rold/manifest.json $K/manifest_old.json 2>/dev/null
.bundle/cavity.sh baselines approve --from $work/r0 --baselines $work/base --by gpu_references.sh \
  --why "gpu matrix, fast pipelines, rendered on $(nvidia-smi --query-gpu=name,driver_version --format=csv,noheader | head -1)" > $K/approve.txt 2>&1
echo "== approve: rc $? $(tail -1 $K/approve.txt)"
cp $work/base/approvals.json $K/approvals.json
.bundle/render.sh --matrix gpu --filter '_fast/' --baselines $work/base --out $work/r1 > $K/render1.txt 2>&1
echo "== render 1: rc $?; image files: $(find $work/r1 -name '*.f32z' | wc -l)"
.bundle/cavity.sh gate judge $work/r1 --baselines $work/base --out $work/g1 --quiet > $K/judge1.md 2>&1
echo "== judge 1: rc $? ($(el) s)"; head -3 $K/judge1.md; cp $work/g1/gate.json $K/judge1.json
smi_stop
filter='^corner/(alchemy_fast|hemisphere_fast)/n(16|32)/b4/((exact=0|pyramid_per_level=1|interleave=4)/)?full/1920x1080/(gl|vk)/compute/'
filter+='|^corner/(alchemy|alchemy_fast|hemisphere_fast)/n16/b4/((fused_tail=1|interleave=4)/)?half/1920x1080/(gl|vk)/compute/'
filter+='|^corner/ssdo_fast/n16/b4/full/1920x1080/(gl|vk)/compute/'
smi_start $K/clocks.csv
.bundle/run.sh --sweep gpu --benchmark_filter="$filter" --benchmark_repetitions=10 \
  --benchmark_enable_random_interleaving=true --max-time 0.3 \
  --benchmark_out=$K/kernels2.json --benchmark_out_format=json > $K/kernels2.txt 2> $K/kernels2.err
echo "== kernels2: rc $? ($(el) s)"
smi_stop
tar czf $OUT/final.tgz -C /tmp keep; ls -la $OUT
echo "all: $(el) s"
