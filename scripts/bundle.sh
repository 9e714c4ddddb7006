#!/usr/bin/env bash
# Packs a self-contained folder for the GPU machine (../shared/docs/GPU.md):
# the benchmark runner and every shared library it needs that a stock Ubuntu
# 24.04 with only the NVIDIA driver lacks. The GL/Vulkan loaders come from the
# .gl/ Debian packages the device recipe unpacks; OpenImageIO is not needed
# (cavity_bench writes JSON only).
#   scripts/bundle.sh [DIR]   (default .bundle; must stay under 40 MiB)
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-.bundle}"
build="${BUILD_DIR:-build}"
cmake --build "$build" --target cavity_bench >/dev/null
rm -rf "$out"
mkdir -p "$out/lib"
cp "$build/bench/cavity_bench" "$out/"
strip "$out/cavity_bench"
# Libraries resolved by the loader here, minus what every glibc system and the
# GPU machine's loaders provide.
system='^(linux-vdso|libc\.so|libm\.so|libdl\.so|librt\.so|libpthread\.so|ld-linux|libstdc\+\+|libgcc_s|libvulkan|libEGL|libGL|libOpenGL|libGLX|libGLdispatch|libX|libxcb)'
ldd "$out/cavity_bench" | awk '/=>/ {print $1, $3}' | while read -r name path; do
  if ! [[ "$name" =~ $system ]]; then cp -L "$path" "$out/lib/"; fi
done
cat > "$out/run.sh" <<'RUN'
#!/usr/bin/env bash
# Runs the benchmark sweep on this machine; arguments go to cavity_bench.
here="$(cd "$(dirname "$0")" && pwd)"
export LD_LIBRARY_PATH="$here/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
exec "$here/cavity_bench" "$@"
RUN
chmod +x "$out/run.sh"
size=$(du -sm "$out" | cut -f1)
echo "bundle: $out ($size MiB): $(ls "$out/lib" | tr '\n' ' ')"
if [ "$size" -gt 40 ]; then echo "bundle: over the 40 MiB limit" >&2; exit 1; fi
