#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Set up a fresh Debian (bookworm) machine, build, and run one job:
#   bash scripts/bootstrap.sh demo   # build and run `normalmap demo`: renders normalmap-demo.png
#                                    # in the current folder
#   bash scripts/bootstrap.sh test   # build and run every test, compile the library for ARM
#                                    # (scripts/portability.sh), build and test the ParaView
#                                    # plugin (scripts/paraview.sh), the same tests and a short
#                                    # fuzz run under ASan + UBSan, then every test against an
#                                    # OSMesa VTK with no X server (what CI runs)
#   bash scripts/bootstrap.sh bench  # build and run the benchmark set (scripts/bench.sh): writes
#                                    # docs/benchmarks.md and docs/benchmarks.png; with
#                                    # MIKKTSPACE_REFERENCE_DIR=<a clone of
#                                    # https://github.com/mmikk/MikkTSpace> it also compares
#                                    # MikkTSpace with the original mikktspace.c
#   bash scripts/bootstrap.sh osmesa # every test against a VTK 9.1 with OSMesa, built once from
#                                    # Debian's source into a cache folder, with no X server
#                                    # (scripts/osmesa.sh; the test job runs it last)
# Installs only Debian packages, and only those missing. BUILD_DIR overrides ./build.
set -euo pipefail
job="${1:-demo}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$root/scripts/common.sh"
build="${BUILD_DIR:-$root/build}"

# The OSMesa job has its own set-up (scripts/osmesa.sh): a VTK of its own, built once and cached.
[ "$job" != osmesa ] || exec bash "$root/scripts/osmesa.sh"

# clang-14 + libclang-rt-14-dev: the sanitizer and libFuzzer build (scripts/sanitize.sh);
# nlohmann-json3-dev + libstb-dev: tinygltf compiled from its header in that build.
# python3-vtk9 + libpython3-dev: the Python package and its tests (libvtk9-dev pulls them in, as
# it does libpng-dev and libjpeg-dev, which the normalmap tool decodes embedded images with).
packages=(build-essential cmake libvtk9-dev libglm-dev libgtest-dev libbenchmark-dev
  libtinygltf-dev xvfb xauth clang-14 libclang-rt-14-dev nlohmann-json3-dev libstb-dev
  python3-vtk9 libpython3-dev libpng-dev libjpeg-dev)
# g++-aarch64-linux-gnu: the test job compiles the library for 64-bit ARM (scripts/portability.sh).
[ "$job" != test ] || packages+=(g++-aarch64-linux-gnu)
# ccache: compiled objects kept outside the checkout (below).
packages+=(ccache)
install_missing "${packages[@]}"

# Every build below (this one, ParaView's, the sanitizer and OSMesa module builds, and the
# builds ctest runs) compiles through ccache, with its objects in the cache folder the OSMesa VTK
# also lives in: a fresh clone then recompiles only what changed. Paths are hashed relative to
# the checkout, so clones in other folders share the objects. No writable cache folder: no
# ccache, the builds compile everything.
cache="${NORMALMAPPING_CACHE:-/var/cache/normalmapping}"
if ! mkdir -p "$cache" 2>/dev/null || [ ! -w "$cache" ]; then
  [ "$(id -u)" -eq 0 ] || { sudo mkdir -p "$cache" && sudo chown "$(id -u):$(id -g)" "$cache"; } ||
    true
fi
if mkdir -p "$cache/ccache" 2>/dev/null && [ -w "$cache/ccache" ]; then
  export CCACHE_DIR="$cache/ccache" CCACHE_BASEDIR="$root" CCACHE_NOHASHDIR=true
  export CMAKE_C_COMPILER_LAUNCHER=ccache CMAKE_CXX_COMPILER_LAUNCHER=ccache
fi

# The original mikktspace.c is not part of this repository: its folder, when given, is compiled
# into BenchMikkTSpace (a build configured with it keeps it until configured with another).
reference=()
[ -z "${MIKKTSPACE_REFERENCE_DIR:-}" ] ||
  reference=("-DNORMALMAPPING_MIKKTSPACE_REFERENCE_DIR=$(cd "$MIKKTSPACE_REFERENCE_DIR" && pwd)")

# The test job builds with compiler warnings as errors: a warning fails CI.
strict=()
[ "$job" != test ] || strict=(-DNORMALMAPPING_WARNINGS_AS_ERRORS=ON)

echo "== configuring and building in $build"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_EXPORT_COMPILE_COMMANDS=ON \
  "${reference[@]}" "${strict[@]}" >/dev/null
cmake --build "$build" -j "$(nproc)" 2>&1 | grep -E "error|warning: |Error" || true
cmake --build "$build" -j "$(nproc)" >/dev/null

case "$job" in
  demo)
    # Debian's VTK renders through X only (no OSMesa): the demo gets a private Xvfb server, as
    # the rendering tests do. A VTK without X (OSMesa, EGL) renders with no X server at all.
    mode=offscreen
    if grep -qs "^#define VTK_USE_X" /usr/include/vtk-*/vtkRenderingOpenGLConfigure.h; then
      mode=xvfb
    fi
    "$root/Testing/Rendering/RunHeadless.sh" "$mode" "$build/bin/normalmap" demo
    echo "== the picture is $(pwd)/normalmap-demo.png"
    ;;
  test)
    (cd "$build" && ctest --output-on-failure -j "$(nproc)")
    echo "== the library compiled for 64-bit ARM"
    bash "$root/scripts/portability.sh" "$build"
    echo "== the ParaView plugin, built against ParaView's VTK, and its pvbatch tests"
    NORMALMAP_TOOL="$build/bin/normalmap" bash "$root/scripts/paraview.sh"
    echo "== the same tests and a short fuzz run under AddressSanitizer + UBSan"
    bash "$root/scripts/sanitize.sh"
    echo "== every test again against a VTK with OSMesa, with no X server"
    bash "$root/scripts/osmesa.sh"
    ;;
  bench)
    bash "$root/scripts/bench.sh" --build "$build"
    ;;
  *)
    echo "usage: $0 demo|test|bench|osmesa" >&2
    exit 2
    ;;
esac
