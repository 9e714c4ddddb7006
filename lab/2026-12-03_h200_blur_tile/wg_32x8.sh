#!/bin/sh
# cavity_bench of .bundle with every pass in 32x8 workgroups (CAVITY_WORKGROUP)
here="$(cd "$(dirname "$0")/../.." && pwd)"
export CAVITY_WORKGROUP=32x8
export LD_LIBRARY_PATH="$here/.bundle/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
exec "$here/.bundle/cavity_bench" "$@"
