#!/usr/bin/env bash
# Builds cavity_bench at several commits and packs them for one call on the GPU
# machine (docs/history.md, "A history measured in one call"): one stripped
# binary per commit, the libraries they need once, and commits.tsv (commit,
# parent, committer date, subject) for `cavity history ingest`. The builds
# share one worktree and one build folder, oldest commit first, so each
# rebuilds only what changed; they are kept in .history-builds/ and reused.
#   scripts/history_bundle.sh [OUT (.bundle-history.tar.xz)] COMMIT...
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
out="${1:?OUT.tar.xz COMMIT...}"
shift
[ $# -ge 2 ] || { echo "history_bundle: give at least two commits" >&2; exit 2; }
cache="$root/.history-builds"
wt="$cache/worktree"
mkdir -p "$cache/bin"
if [ ! -d "$wt" ]; then git worktree add --detach "$wt" HEAD >/dev/null; fi
# Oldest first, so the shared build folder moves forward.
mapfile -t commits < <(for c in "$@"; do
  full=$(git rev-parse --verify "$c^{commit}") || { echo "history_bundle: $c: not a commit" >&2; exit 2; }
  echo "$(git show -s --format=%ct "$full") $full"
done | sort -n | cut -d' ' -f2)
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
mkdir -p "$stage/history/lib"
: > "$stage/history/commits.tsv"
for c in "${commits[@]}"; do
  short=${c:0:12}
  if [ ! -x "$cache/bin/$short" ]; then
    echo "history_bundle: building $short ($(git show -s --format=%s "$c" | cut -c1-60))"
    git -C "$wt" checkout -q --detach "$c"
    cmake -S "$wt" -B "$cache/build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
    cmake --build "$cache/build" --target cavity_bench >/dev/null
    cp "$cache/build/bench/cavity_bench" "$cache/bin/$short"
    strip "$cache/bin/$short"
  fi
  cp "$cache/bin/$short" "$stage/history/bench_$short"
  printf '%s\t%s\t%s\t%s\n' "$c" "$(git rev-parse --verify -q "$c^" || true)" \
    "$(git show -s --format=%cI "$c")" "$(git show -s --format=%s "$c" | cut -c1-100)" >> "$stage/history/commits.tsv"
done
# The libraries the binaries need that the GPU machine lacks (as scripts/bundle.sh decides).
system='^(linux-vdso|libc\.so|libm\.so|libdl\.so|librt\.so|libpthread\.so|ld-linux|libstdc\+\+|libgcc_s|libz\.so|libvulkan|libEGL|libGL|libOpenGL|libGLX|libGLdispatch|libX|libxcb)'
for b in "$stage"/history/bench_*; do ldd "$b" | awk '/=>/ {print $1, $3}'; done | sort -u | while read -r name path; do
  if ! [[ "$name" =~ $system ]]; then cp -L "$path" "$stage/history/lib/"; fi
done
tar -C "$stage" -cJf "$out" history
echo "history_bundle: $out ($(du -h "$out" | cut -f1)): ${#commits[@]} commits, $(ls "$stage/history/lib" | wc -l) libraries"
