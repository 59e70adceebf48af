#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Builds the project with clang, AddressSanitizer + UndefinedBehaviorSanitizer (+ LeakSanitizer,
# part of ASan) and the libFuzzer targets in ./build-asan (ASAN_BUILD_DIR overrides), then
#   bash scripts/sanitize.sh                   # every ctest test there, the fuzz smoke runs too
#   bash scripts/sanitize.sh fuzz SECONDS      # fuzzes FuzzTangentFrames for SECONDS (local use)
#   bash scripts/sanitize.sh fuzz SECONDS gltf # fuzzes FuzzNormalMapGLTF (the tool's glTF path)
# Any sanitizer report fails the run. tinygltf is compiled from its header in this build
# (NORMALMAPPING_TINYGLTF_FROM_SOURCE), so its own memory accesses are checked too. Needs the
# Debian packages clang-14, libclang-rt-14-dev, nlohmann-json3-dev and libstb-dev
# (scripts/bootstrap.sh installs them). `bash scripts/bootstrap.sh test` runs the first form
# after the normal build and tests.
set -euo pipefail
job="${1:-test}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${ASAN_BUILD_DIR:-$root/build-asan}"
jobs="$(nproc)"
[ "$jobs" -le 2 ] || jobs=2

# halt_on_error + -fno-sanitize-recover=all: the first report ends the process with an error.
# VTK, TBB and Mesa are uninstrumented shared libraries: ASan still sees their heap (malloc is
# intercepted) and LeakSanitizer their leaks. Mesa's unloaded driver is kept mapped (see
# sanitizer/keep-modules-loaded.c) so its allocations stay attributable; the one suppression,
# a leak inside libpng when VTK's glTF reader loads images, is explained in sanitizer/lsan.supp.
# intercept_tls_get_addr=0: LeakSanitizer (clang 14) tracks dynamic TLS blocks through
# __tls_get_addr and guesses a block's size from a glibc 2.19 header when the block's address is
# 16 past a page boundary; with Debian's glibc 2.36 that guess can read garbage, and the leak
# check at exit then crashes in ScanRangeForPointers ("Tracer caught signal 11",
# google/sanitizers#1322). Tests whose filters run on TBB's worker threads (TestNormalMapSettings)
# crash there after passing; with VTK's STDThread or Sequential backend, with use_tls=0 or with
# this option they do not. Without the interception those blocks are ordinary heap blocks to
# LeakSanitizer, reachable through the threads' own TLS, which it still scans.
export ASAN_OPTIONS="halt_on_error=1:abort_on_error=1:detect_leaks=1:strict_string_checks=1:intercept_tls_get_addr=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
export LSAN_OPTIONS="suppressions=$root/scripts/sanitizer/lsan.supp:print_suppressions=0"

flags="-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer"
echo "== configuring and building with ASan + UBSan in $build"
# No Python wrapping here (so no Python tests): an ASan-built extension can only be loaded into
# Debian's uninstrumented python3 with libasan preloaded into the interpreter, whose own
# allocator and leaks ASan would then report. The normal build runs the Python tests.
# tinygltf is compiled here from Debian's header (NORMALMAPPING_TINYGLTF_FROM_SOURCE), not linked
# as the shared library, so that ASan, UBSan and libFuzzer see inside it.
CC=clang-14 CXX=clang++-14 cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DNORMALMAPPING_BUILD_BENCHMARKS=OFF -DNORMALMAPPING_BUILD_FUZZERS=ON \
  -DNORMALMAPPING_WRAP_PYTHON=OFF -DNORMALMAPPING_TINYGLTF_FROM_SOURCE=ON \
  -DNORMALMAPPING_WARNINGS_AS_ERRORS=ON >/dev/null
cmake --build "$build" -j "$jobs" 2>&1 | grep -E "error|warning: |Error" || true
cmake --build "$build" -j "$jobs" >/dev/null

if [ "$job" = fuzz ]; then
  # New inputs go to build-asan/fuzz-corpus[-gltf] (kept between runs), crashes to
  # build-asan/fuzz-artifacts[-gltf]; the checked-in corpus is only read.
  if [ "${3:-tangents}" = gltf ]; then
    mkdir -p "$build/fuzz-corpus-gltf" "$build/fuzz-artifacts-gltf"
    exec "$build/bin/FuzzNormalMapGLTF" -max_total_time="${2:-600}" -max_len=16384 \
      -dict="$root/Testing/Fuzz/gltf.dict" -print_final_stats=1 \
      -artifact_prefix="$build/fuzz-artifacts-gltf/" \
      "$build/fuzz-corpus-gltf" "$root/Testing/Fuzz/gltf-corpus"
  fi
  mkdir -p "$build/fuzz-corpus" "$build/fuzz-artifacts"
  exec "$build/bin/FuzzTangentFrames" -max_total_time="${2:-600}" -max_len=4096 \
    -print_final_stats=1 -artifact_prefix="$build/fuzz-artifacts/" \
    "$build/fuzz-corpus" "$root/Testing/Fuzz/corpus"
fi

clang-14 -shared -fPIC -O2 -o "$build/libkeep-modules-loaded.so" \
  "$root/scripts/sanitizer/keep-modules-loaded.c"

cd "$build"
# Every test, also those added later (rendering tests that run under xvfb-run included),
# except the packaging tests: they configure and compile the sources again in nested projects
# with their own (unsanitized) flags, so they check the CMake packaging, not memory safety,
# and would add minutes for nothing here (the normal build's ctest runs them).
LD_PRELOAD="$build/libkeep-modules-loaded.so" \
  ctest --output-on-failure -j "$jobs" -LE '^packaging$'
