#!/usr/bin/env bash
# Set up, build, and run every test (ctest) on both backends with the Vulkan
# validation layer on. Extra arguments go to ctest (e.g. -R Alchemy).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
build="${BUILD_DIR:-build}"
cd "$build"
exec ctest --output-on-failure -j "$(nproc)" "$@"
