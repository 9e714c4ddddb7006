#!/usr/bin/env bash
# One CTest test of the gate spread over GPUs (tests/CMakeLists.txt, label
# `gate`):
#
#   ctest_gate_shard.sh shard CAVITY I N MATRIX BASELINES OUTROOT [FILTER]
#   ctest_gate_shard.sh merge CAVITY N OUTROOT
#   ctest_gate_shard.sh bench CAVITY_BENCH I N OUTROOT [FILTER]
#   ctest_gate_shard.sh bench-merge N OUTROOT
#
# `shard` runs `cavity gate --shard I/N` on the GPU CTest gave the test: with
# --resource-spec-file, CTest sets CTEST_RESOURCE_GROUP_COUNT=1 and
# CTEST_RESOURCE_GROUP_0_GPUS=id:ID,slots:1, and ID is a device index or
# INDEX_J (scripts/ctest_resources.py); without a spec it runs on device 0.
# It passes when the shard reached a verdict (gate exit 0 or 1): the verdict
# belongs to `merge`, which joins OUTROOT/0..N-1 into OUTROOT/merged and
# exits as the gate does. CAVITY_GATE_OUT and CAVITY_GATE_FILTER, when set,
# replace OUTROOT and FILTER (a test that runs an inner ctest sets them).
# `bench` runs every N-th benchmark from the I-th of cavity_bench's list (as
# --benchmark_filter, regex FILTER first; CAVITY_BENCH_FILTER replaces it)
# on the test's GPU into OUTROOT/bench-I.json; `bench-merge` joins them into
# OUTROOT/bench.json for `cavity compare` and scripts/charts/charts.py.
set -uo pipefail
resource_device() {
    # The device CTest gave this test: 0 without a resource spec.
    device=0
    if [ -n "${CTEST_RESOURCE_GROUP_COUNT:-}" ]; then
        if [ "$CTEST_RESOURCE_GROUP_COUNT" != 1 ]; then
            echo "ctest_gate_shard.sh: CTEST_RESOURCE_GROUP_COUNT=$CTEST_RESOURCE_GROUP_COUNT: a shard asks for one group (gpus:1)" >&2
            exit 2
        fi
        # CTEST_RESOURCE_GROUP_0 lists the group's resource types.
        if [[ ",${CTEST_RESOURCE_GROUP_0:-}," != *,gpus,* ]]; then
            echo "ctest_gate_shard.sh: CTEST_RESOURCE_GROUP_0='${CTEST_RESOURCE_GROUP_0:-}': the group has no gpus (RESOURCE_GROUPS gpus:1)" >&2
            exit 2
        fi
        gpus=${CTEST_RESOURCE_GROUP_0_GPUS:-}
        # "id:3_1,slots:1" -> 3
        if [[ ! $gpus =~ ^id:([0-9]+)(_[0-9]+)?,slots:[0-9]+$ ]]; then
            echo "ctest_gate_shard.sh: CTEST_RESOURCE_GROUP_0_GPUS='$gpus': must be id:K,slots:M or id:K_J,slots:M (K a device index; scripts/ctest_resources.py)" >&2
            exit 2
        fi
        device=${BASH_REMATCH[1]}
    fi
}

mode=${1:-}
case "$mode" in
shard)
    [ $# -ge 7 ] || { echo "ctest_gate_shard.sh shard: needs CAVITY I N MATRIX BASELINES OUTROOT [FILTER]" >&2; exit 2; }
    cavity=$2 i=$3 n=$4 matrix=$5 baselines=$6
    root=${CAVITY_GATE_OUT:-$7}
    filter=${CAVITY_GATE_FILTER-${8:-}}
    resource_device
    mkdir -p "$root/$i"
    echo "${CTEST_RESOURCE_GROUP_0_GPUS:-none}" >"$root/$i/resource.txt"
    args=(gate --matrix "$matrix" --baselines "$baselines" --shard "$i/$n" --device "$device" --out "$root/$i")
    [ -n "$filter" ] && args+=(--filter "$filter")
    echo "shard $i/$n on device $device (${CTEST_RESOURCE_GROUP_0_GPUS:-no resource spec}): $cavity ${args[*]}"
    # The shard's variables of an outer test runner would conflict with --shard.
    env -u GTEST_SHARD_INDEX -u GTEST_TOTAL_SHARDS -u TEST_SHARD_INDEX -u TEST_TOTAL_SHARDS "$cavity" "${args[@]}" >"$root/$i/console.txt" 2>&1
    rc=$?
    tail -n 3 "$root/$i/console.txt"
    [ $rc -le 1 ] && exit 0
    cat "$root/$i/console.txt" >&2
    exit $rc
    ;;
merge)
    [ $# -ge 4 ] || { echo "ctest_gate_shard.sh merge: needs CAVITY N OUTROOT" >&2; exit 2; }
    cavity=$2 n=$3
    root=${CAVITY_GATE_OUT:-$4}
    dirs=()
    for ((k = 0; k < n; ++k)); do dirs+=("$root/$k"); done
    exec "$cavity" gate merge "${dirs[@]}" --out "$root/merged"
    ;;
bench)
    [ $# -ge 5 ] || { echo "ctest_gate_shard.sh bench: needs CAVITY_BENCH I N OUTROOT [FILTER]" >&2; exit 2; }
    bench=$2 i=$3 n=$4
    root=${CAVITY_GATE_OUT:-$5}
    filter=${CAVITY_BENCH_FILTER-${6:-}}
    resource_device
    mkdir -p "$root"
    list=$("$bench" --device "$device" --benchmark_list_tests ${filter:+"--benchmark_filter=$filter"}) || exit $?
    # Every N-th name from the I-th, as one anchored alternation.
    mine=$(printf '%s\n' "$list" | awk -v i="$i" -v n="$n" 'NF && (NR - 1) % n == i' |
        sed 's/[][\.^$*+?(){}|]/\\&/g' | paste -sd '|')
    if [ -z "$mine" ]; then
        echo "bench shard $i/$n: no benchmarks (${filter:-no filter})"
        printf '{"context": {}, "benchmarks": []}\n' >"$root/bench-$i.json"
        exit 0
    fi
    echo "bench shard $i/$n on device $device: $(printf '%s\n' "$list" | awk -v i="$i" -v n="$n" 'NF && (NR - 1) % n == i' | wc -l) benchmarks"
    exec "$bench" --device "$device" "--benchmark_filter=^($mine)\$" --benchmark_out="$root/bench-$i.json" \
        --benchmark_out_format=json
    ;;
bench-merge)
    [ $# -ge 3 ] || { echo "ctest_gate_shard.sh bench-merge: needs N OUTROOT" >&2; exit 2; }
    n=$2
    root=${CAVITY_GATE_OUT:-$3}
    exec python3 - "$n" "$root" <<'PY'
import json, os, sys
n, root = int(sys.argv[1]), sys.argv[2]
merged = None
for k in range(n):
    with open(os.path.join(root, f"bench-{k}.json")) as f:
        part = json.load(f)
    if merged is None or not merged.get("context"):
        merged = {"context": part.get("context", {}), "benchmarks": []}
    merged["benchmarks"] += part["benchmarks"]
merged["context"]["cavity_shards"] = n
with open(os.path.join(root, "bench.json.tmp"), "w") as f:
    json.dump(merged, f, indent=1)
os.replace(os.path.join(root, "bench.json.tmp"), os.path.join(root, "bench.json"))
print(f"{root}/bench.json: {len(merged['benchmarks'])} entries from {n} shards")
PY
    ;;
*)
    echo "ctest_gate_shard.sh: '$mode': must be shard, merge, bench or bench-merge" >&2
    exit 2
    ;;
esac
