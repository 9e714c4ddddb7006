#!/usr/bin/env bash
# The tests on an AddressSanitizer + UndefinedBehaviorSanitizer build
# (CMake option CAVITY_SANITIZE) in build-asan/. Any ASan or UBSan report
# fails the test that made it. Leak checking is off: Mesa's llvmpipe keeps
# JIT-allocated blocks to exit, from code LSan cannot name.
# Extra arguments go to ctest. About 16 minutes to build on 2 cores and 8 to
# run, which is why CI (scripts/test.sh) does not run it yet.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCAVITY_WERROR=ON -DCAVITY_SANITIZE=ON >/dev/null
cmake --build build-asan -j "$(nproc)"
cd build-asan
export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
exec ctest --output-on-failure -j "$(nproc)" -LE '^(gate|bench)$' "$@"
