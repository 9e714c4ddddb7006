#!/usr/bin/env bash
# Packs a self-contained folder for the GPU machine (docs/gpu.md):
# the benchmark runner, the gate's render binary, every shared library they
# need that a stock Ubuntu 24.04 with only the NVIDIA driver lacks, and the
# one repository file cavity_render reads at run time (baselines/matrices.json;
# the kernel sources are compiled in). The GL/Vulkan loaders come from the
# .gl/ Debian packages the device recipe unpacks; OpenImageIO is not needed
# (cavity_bench writes JSON, cavity_render a render folder of zlib images).
#   scripts/bundle.sh [DIR]   (default .bundle; must stay under 56 MiB: the device
#   tool carries 64 MiB; libcurl and its TLS, Kerberos and LDAP libraries, for
#   an HTTP image store there, are 17 MiB of it)
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-.bundle}"
build="${BUILD_DIR:-build}"
# BUNDLE_BINARIES picks fewer (the device tool carries 64 MiB with the
# repository): "cavity_bench" alone for the timing scripts, "cavity_bench
# cavity" for cavity ab; cavity and its libraries (libcurl, libpq, SQLite)
# are about half the bundle.
binaries=(${BUNDLE_BINARIES:-cavity_bench cavity_render cavity})
declare -A path=([cavity_bench]=bench/cavity_bench [cavity_render]=render/cavity_render [cavity]=harness/cavity)
for b in "${binaries[@]}"; do
  [ -n "${path[$b]:-}" ] || { echo "bundle: BUNDLE_BINARIES: $b: not one of cavity_bench cavity_render cavity" >&2; exit 2; }
done
cmake --build "$build" --target "${binaries[@]}" >/dev/null
rm -rf "$out"
mkdir -p "$out/lib" "$out/baselines"
# cavity travels without its OpenImageIO module: there it judges render
# folders whose images are all approved by digest (docs/gate.md), which
# reads no image file; anything that needs pixels says it cannot load the module.
for b in "${binaries[@]}"; do
  cp "$build/${path[$b]}" "$out/"
  strip "$out/$b"
done
# matrices.json to render, approvals.json to leave approved images out, the
# tolerances and budgets to judge there (cavity_render --store, cavity gate judge).
cp baselines/matrices.json baselines/manifest.json baselines/budgets.json "$out/baselines/"
# BUNDLE_KERNELS: kernel package folders (':' between them) that travel in
# kernels/; every wrapper loads them (CAVITY_KERNELS), so the GPU machine
# sees the package kernels as here (docs/packages.md).
if [ -n "${BUNDLE_KERNELS:-}" ]; then
  mkdir -p "$out/kernels"
  IFS=: read -r -a kernel_dirs <<< "$BUNDLE_KERNELS"
  for d in "${kernel_dirs[@]}"; do
    [ -d "$d" ] || { echo "bundle: BUNDLE_KERNELS: $d: no such folder" >&2; exit 2; }
    # A package folder, or a folder of them: each package becomes kernels/<folder>.
    if [ -f "$d/kernel.toml" ]; then cp -r "$d" "$out/kernels/"; else cp -r "$d"/. "$out/kernels/"; fi
  done
fi
[ -f baselines/approvals.json ] && cp baselines/approvals.json "$out/baselines/"
# Libraries resolved by the loader here, minus what every glibc system and the
# GPU machine's loaders provide. libz is part of every Linux base system
# (Ubuntu's zlib1g is "required"), and the system's own must win: the NVIDIA
# driver's libraries load it too, and ours (Debian 12's) is older.
system='^(linux-vdso|libc\.so|libm\.so|libdl\.so|librt\.so|libpthread\.so|ld-linux|libstdc\+\+|libgcc_s|libz\.so|libvulkan|libEGL|libGL|libOpenGL|libGLX|libGLdispatch|libX|libxcb)'
for exe in "${binaries[@]}"; do
  ldd "$out/$exe" | awk '/=>/ {print $1, $3}'
done | sort -u | while read -r name path; do
  if ! [[ "$name" =~ $system ]]; then cp -L "$path" "$out/lib/"; fi
done
cat > "$out/run.sh" <<'RUN'
#!/usr/bin/env bash
# Runs the benchmark sweep on this machine; arguments go to cavity_bench.
here="$(cd "$(dirname "$0")" && pwd)"
export LD_LIBRARY_PATH="$here/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
[ -d "$here/kernels" ] && export CAVITY_KERNELS="$here/kernels${CAVITY_KERNELS:+:$CAVITY_KERNELS}"
exec "$here/cavity_bench" "$@"
RUN
cat > "$out/render.sh" <<'RENDER'
#!/usr/bin/env bash
# Renders a gate matrix into a render folder for `cavity gate judge`, or runs
# `quality`; arguments go to cavity_render. The matrices are the bundle's
# copy of baselines/matrices.json unless --baselines says otherwise.
here="$(cd "$(dirname "$0")" && pwd)"
export LD_LIBRARY_PATH="$here/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
[ -d "$here/kernels" ] && export CAVITY_KERNELS="$here/kernels${CAVITY_KERNELS:+:$CAVITY_KERNELS}"
if [ "${1:-}" != quality ] && [[ " $* " != *" --baselines "* ]]; then
  set -- "$@" --baselines "$here/baselines"
fi
exec "$here/cavity_render" "$@"
RENDER
cat > "$out/cavity.sh" <<'CAVITY'
#!/usr/bin/env bash
# Runs cavity (cavity ab, cavity gate judge) with the bundle's libraries.
here="$(cd "$(dirname "$0")" && pwd)"
export LD_LIBRARY_PATH="$here/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
[ -d "$here/kernels" ] && export CAVITY_KERNELS="$here/kernels${CAVITY_KERNELS:+:$CAVITY_KERNELS}"
exec "$here/cavity" "$@"
CAVITY
# The binaries and the larger libraries travel xz-compressed (about a third
# of their size: with all three programs the bundle and the repository no
# longer fit the 64 MiB the device tool carries otherwise). unpack.sh
# restores them in place on first use; each wrapper and scripts/gpu_env.sh
# call it, and it does nothing once they are unpacked. BUNDLE_XZ=0 leaves
# them as they are; BUNDLE_XZ=1 to 9 is xz's preset (default 6; 1 packs a
# sanitizer build in a fraction of the time, a little larger).
cat > "$out/unpack.sh" <<'UNPACK'
#!/usr/bin/env bash
# Unpacks this bundle's xz-compressed files in place, each through a
# temporary name and a rename, so that two wrappers started at once cannot
# see half a file.
here="$(cd "$(dirname "$0")" && pwd)"
for f in "$here"/*.xz "$here"/lib/*.xz; do
  [ -e "$f" ] || continue
  target="${f%.xz}"
  tmp="$target.unpack.$$"
  if ! xz -dc "$f" > "$tmp" 2>/dev/null; then
    rm -f "$tmp"
    [ -e "$f" ] || continue   # another wrapper unpacked it meanwhile
    echo "unpack.sh: $f: xz cannot decompress it" >&2
    exit 1
  fi
  [ "$(dirname "$f")" = "$here" ] && chmod +x "$tmp"
  mv -f "$tmp" "$target" && rm -f "$f"
done
UNPACK
for w in run.sh render.sh cavity.sh; do
  sed -i 's|^here="$(cd "$(dirname "$0")" \&\& pwd)"$|&\n"$here/unpack.sh" \|\| exit 1|' "$out/$w"
done
chmod +x "$out/run.sh" "$out/render.sh" "$out/cavity.sh" "$out/unpack.sh"
preset="${BUNDLE_XZ:-6}"
case "$preset" in [0-9]) ;; *) echo "bundle: BUNDLE_XZ=$preset: must be 0 (no compression) or an xz preset 1..9" >&2; exit 2 ;; esac
if [ "$preset" != 0 ]; then
  xz -T0 "-$preset" "${binaries[@]/#/$out/}"
  find "$out/lib" -type f -size +1M -exec xz "-$preset" {} +
fi
size=$(du -sm "$out" | cut -f1)
echo "bundle: $out ($size MiB): ${binaries[*]} baselines/ lib/: $(ls "$out/lib" | tr '\n' ' ')"
# BUNDLE_MAX_MIB: a dry run's unstripped sanitizer build is larger, and stays here.
limit="${BUNDLE_MAX_MIB:-56}"
if [ "$size" -gt "$limit" ]; then echo "bundle: $size MiB, over the $limit MiB limit" >&2; exit 1; fi
