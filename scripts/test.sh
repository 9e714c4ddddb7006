#!/usr/bin/env bash
# Set up, build, and run every test (ctest) on both backends with the Vulkan
# validation layer on. Extra arguments go to ctest (e.g. -R Alchemy).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
build="${BUILD_DIR:-build}"
cd "$build"
# The `gate` label is the ci gate once more, spread over GPUs (README,
# "Spreading a gate over machines"); it runs when asked for with -L.
case " $* " in
*" -L "*|*" -L"*) exec ctest --output-on-failure -j "$(nproc)" "$@" ;;
*) exec ctest --output-on-failure -j "$(nproc)" -LE '^gate$' "$@" ;;
esac
