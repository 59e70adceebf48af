#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The module and its tests against a newer VTK than Debian's:
#   bash scripts/newvtk.sh <VTK source tree>         # builds that VTK once, into a cache folder
#   bash scripts/newvtk.sh <VTK build or install>    # uses the VTK found there as it is
#
# Debian bookworm has VTK 9.1 (and ParaView's 9.2). VTK 9.3 replaced the composite mapper the
# module extends (vtkCompositePolyDataMapper2, removed in 9.5, gave way to
# vtkCompositePolyDataMapper and its batched delegates), and VTK 9.6 added cell storages the
# filter converts. A source tree (9.3 or later: a release tarball, or a git checkout of a release
# tag) is built with X rendering and the modules the tests use into
#   ${NORMALMAPPING_CACHE:-/var/cache/normalmapping}/vtk-<version>-x
# and reused while the key recorded there (the version and the configure options) matches; a
# folder holding a vtk-config.cmake (a VTK build tree or install prefix) is used directly. Then
# the module is built against that VTK in ${NEWVTK_BUILD_DIR:-build-newvtk}, without Python
# wrapping (Debian's Python VTK is 9.1) or benchmarks, and ctest runs every other test, the
# rendering tests on a private Xvfb each (or offscreen, for a VTK built without X).
#
# VTK is not a Debian package at these versions, so the VTK is the caller's; only the build
# dependencies come from Debian. Building VTK takes about an hour on two cores, which is why
# the README's test command does not run this job. Compiles run under `nice -n 19` with
# ${NEWVTK_JOBS:-2} jobs.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$root/scripts/common.sh"
given="$(cd "${1:?usage: bash scripts/newvtk.sh <VTK source tree, build or install>}" && pwd)"
cache="${NORMALMAPPING_CACHE:-/var/cache/normalmapping}"
build="${NEWVTK_BUILD_DIR:-$root/build-newvtk}"
jobs="${NEWVTK_JOBS:-2}"

# The version of the VTK source tree $given, from its CMake/vtkVersion.cmake.
source_version() {
  local part
  for part in MAJOR MINOR BUILD; do
    sed -n "s/^set(VTK_${part}_VERSION \([0-9]*\)).*/\1/p" "$given/CMake/vtkVersion.cmake"
  done | paste -sd. -
}

# Builds the source tree $given once into the cache; sets vtk_dir to its CMake package.
build_from_source() {
  local version
  version="$(source_version)"
  case "$version" in
    9.[0-2].*)
      echo "VTK $version: the test command runs every test on Debian's VTK 9.1" >&2
      exit 2
      ;;
  esac
  local prefix="$cache/vtk-$version-x"
  local options=(-DCMAKE_BUILD_TYPE=Release "-DCMAKE_C_FLAGS_RELEASE=-O2 -DNDEBUG"
    "-DCMAKE_CXX_FLAGS_RELEASE=-O2 -DNDEBUG" -DBUILD_SHARED_LIBS=ON -DCMAKE_INSTALL_LIBDIR=lib
    -DCMAKE_INSTALL_RPATH="$prefix/lib" -DVTK_SMP_IMPLEMENTATION_TYPE=TBB
    -DVTK_BUILD_ALL_MODULES=OFF -DVTK_BUILD_TESTING=OFF -DVTK_BUILD_EXAMPLES=OFF
    -DVTK_WRAP_PYTHON=OFF -DVTK_USE_MPI=OFF -DVTK_ENABLE_REMOTE_MODULES=OFF)
  vtk_module_options options
  local key="VTK $version ${options[*]}"
  ensure_writable_dir "$cache"
  if [ "$(cat "$prefix/normalmapping-key.txt" 2>/dev/null)" = "$key" ]; then
    echo "== reusing VTK $version in $prefix"
  else
    echo "== VTK $version with X (the modules the tests use), into $prefix"
    rm -rf "$prefix"
    install_vtk "$given" "$cache/work-vtk-$version" "$prefix" "$cache/vtk-$version" "$jobs" \
      "${options[@]}"
    printf '%s\n' "$key" >"$prefix/normalmapping-key.txt"
    rm -rf "$cache/work-vtk-$version"
  fi
  vtk_dir="$prefix/lib/cmake/vtk-${version%.*}"
}

main() {
  install_missing build-essential cmake ninja-build xvfb xauth libx11-dev libxcursor-dev \
    libxt-dev libgl-dev libtbb-dev libgtest-dev libglm-dev libtinygltf-dev nlohmann-json3-dev \
    libstb-dev zlib1g-dev libpng-dev libjpeg-dev
  vtk_dir=""
  if [ -f "$given/CMake/vtkVersion.cmake" ]; then
    build_from_source
  else
    vtk_dir="$(find "$given" -maxdepth 4 -name vtk-config.cmake -printf '%d %h\n' | sort -n |
      head -n 1 | cut -d' ' -f2-)"
    [ -n "$vtk_dir" ] || { echo "$given: neither a VTK source tree nor a VTK package" >&2; exit 2; }
  fi

  echo "== the module against $vtk_dir, in $build"
  build_module "$vtk_dir" "$build" "$jobs" -DNORMALMAPPING_BUILD_BENCHMARKS=OFF
  echo "== every test against the VTK of $vtk_dir"
  # The VTK's libraries, for programs built against an install without an RPATH (the
  # installed-package test's example).
  local libdir="$vtk_dir/lib"
  case "$vtk_dir" in */cmake/vtk-*) libdir="$(cd "$vtk_dir/../.." && pwd)" ;; esac
  (cd "$build" && LD_LIBRARY_PATH="$libdir${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" \
    ctest --output-on-failure -j "$jobs")
}

# One line: bash reads it whole before main starts, so editing this file while a job runs does
# not change what that job does.
main "$@"; exit
