#!/usr/bin/env bash
# Set up, build, and run every test (ctest) on both backends with the Vulkan
# validation layer on. Extra arguments go to ctest (e.g. -R Alchemy).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
build="${BUILD_DIR:-build}"
cd "$build"
# The `gate` and `bench` labels are the ci gate once more and the benchmark
# sweep, spread over GPUs (README, "Spreading the gate over GPUs and
# machines"); they run when asked for with -L.
case " $* " in
*" -L "*|*" -L"*) exec ctest --output-on-failure -j "$(nproc)" "$@" ;;
*) exec ctest --output-on-failure -j "$(nproc)" -LE '^(gate|bench)$' "$@" ;;
esac
