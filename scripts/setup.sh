#!/usr/bin/env bash
# Installs the Debian 12 packages Cavity needs (when missing) and builds it.
# Used by scripts/run.sh and scripts/test.sh; safe to run again.
#   BUILD_DIR (default build, or build-asan with CAVITY_SANITIZE=ON),
#   CAVITY_WERROR=ON to treat warnings as errors, CAVITY_SANITIZE=ON for an
#   AddressSanitizer + UndefinedBehaviorSanitizer build.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake ninja-build pkg-config git
  libvulkan-dev vulkan-validationlayers mesa-vulkan-drivers   # Vulkan loader, Khronos validation, lavapipe
  libegl-dev libopengl-dev libegl-mesa0 libgl1-mesa-dri libepoxy-dev   # EGL/GL via libglvnd, llvmpipe, GL loader
  glslang-dev glslang-tools spirv-tools                         # GLSL -> SPIR-V (glslang links SPIRV-Tools; its CMake config names glslangValidator)
  libopenimageio-dev                                            # EXR/PNG images
  libgtest-dev libgmock-dev libbenchmark-dev                    # tests and benchmarks
  nlohmann-json3-dev                                            # results.json
  libcli11-dev                                                  # command-line flags and --help
  libimath-dev                                                  # half floats (backends/texels; also OpenEXR's)
  libfmt-dev                                                    # text tables (harness/core/text_table.cpp)
  libtomlplusplus-dev                                           # kernel packages: kernel.toml (kernels/package)
  zlib1g-dev                                                    # render folders (cavity_render)
  xz-utils                                                      # scripts/bundle.sh: the GPU bundle, compressed (tests/test_bundle.py)
  libcurl4-openssl-dev                                          # the HTTP image store (harness/store)
  libssl-dev                                                    # SHA-256 image digests (OpenSSL's libcrypto; harness/core/digest.cpp)
  nginx-light openssl                                           # tests/test_store_http.py: a real WebDAV store, with TLS
  python3 python3-matplotlib python3-jsonschema                 # scripts/charts/charts.py; tests/validate_results.py
  python3-xmlschema python3-junitparser                         # tests/validate_junit.py: junit.xml as CI readers take it
  chromium                                                      # the HTML report test (headless screenshot)
  cmark-gfm                                                     # tests/validate_summary.py: summary.md as GitHub renders it
  universal-ctags                                               # tests/code_size.py: function lengths
  libsqlite3-dev                                                # cavity history: the results database in a file
  libpq-dev                                                     # cavity history: the results database on a PostgreSQL server
  libjs-chart.js                                                # cavity history chart: Chart.js, inlined into the page at build time
  postgresql                                                    # tests/test_history_postgres.py: a real server started by the test
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# The commit-msg hook (subjects of at most 72 characters, as `git log
# --oneline` shows them), for a clone; a tarball has no .git to hook.
if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  git config core.hooksPath scripts/hooks
fi

# CAVITY_SANITIZE=ON builds with ASan + UBSan, into build-asan/ unless
# BUILD_DIR says otherwise (CI does this: .ci/run).
sanitize="${CAVITY_SANITIZE:-OFF}"
build="${BUILD_DIR:-$([ "$sanitize" = ON ] && echo build-asan || echo build)}"
# CMake's file API (tests/layering.py reads the link lines there) answers
# the queries it finds when a configure starts: ask before the first one.
mkdir -p "$build/.cmake/api/v1/query" && : > "$build/.cmake/api/v1/query/codemodel-v2"
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCAVITY_WERROR="${CAVITY_WERROR:-OFF}" \
  -DCAVITY_SANITIZE="$sanitize" >/dev/null
cmake --build "$build" -j "$(nproc)"
