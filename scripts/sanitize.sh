#!/usr/bin/env bash
# The tests on an AddressSanitizer + UndefinedBehaviorSanitizer build
# (CMake option CAVITY_SANITIZE) in build-asan/: what CI runs (.ci/run).
# Extra arguments go to ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
CAVITY_SANITIZE=ON exec scripts/test.sh "$@"
