#!/usr/bin/env bash
# Builds rates.cpp against the release build's harness library and runs it.
#   bash lab/2026-12-06_cpu_history_detector/rates.sh [TRIALS] > rates.txt
set -euo pipefail
cd "$(dirname "$0")/../.."
here=lab/2026-12-06_cpu_history_detector
cmake --build build --target cavity_history >/dev/null
g++ -std=c++20 -O2 -Iharness -Ibase -Itests "$here/rates.cpp" build/harness/libcavity_history.a build/harness/libcavity_core.a -o /tmp/cavity_rates
/tmp/cavity_rates "${1:-200}"
