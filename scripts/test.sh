#!/usr/bin/env bash
# Set up, build, and run every test (ctest) on both backends with the Vulkan
# validation layer on. Extra arguments go to ctest (e.g. -R Alchemy).
# CAVITY_SANITIZE=ON runs them on an ASan + UBSan build (CI does: .ci/run).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
build="${BUILD_DIR:-$([ "${CAVITY_SANITIZE:-OFF}" = ON ] && echo build-asan || echo build)}"
cd "$build"
# On a sanitizer build any ASan or UBSan report aborts the test (and the
# programs the Python tests start) that made it. Leak checking is off:
# Mesa's llvmpipe keeps JIT-allocated blocks to exit, from code LSan cannot name.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=0:abort_on_error=1:quarantine_size_mb=16:malloc_context_size=5}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
# The `gate` and `bench` labels are the ci gate once more and the benchmark
# sweep, spread over GPUs (README, "Spreading the gate over GPUs and
# machines"); they run when asked for with -L.
case " $* " in
*" -L "*|*" -L"*) exec ctest --output-on-failure -j "$(nproc)" "$@" ;;
*) exec ctest --output-on-failure -j "$(nproc)" -LE '^(gate|bench)$' "$@" ;;
esac
