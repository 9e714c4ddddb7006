#!/usr/bin/env bash
# The main job: set up, build, and run the default sweep on every backend this
# machine has (Mesa llvmpipe and lavapipe when there is no GPU). Extra
# arguments go to `cavity run` (e.g. --out DIR, --res 1920x1080).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
build="${BUILD_DIR:-build}"
exec "$build/harness/cavity" run --backend all --scene corner,slats --kernel alchemy,alchemy_fast,hemisphere,ssdo \
  --samples 16 --blur 0,4 --resolution full,half --res 320x180 --frames 10 --out out "$@"
