#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The OSMesa test job (bash scripts/bootstrap.sh osmesa): the module's tests, rendering and
# image tests included (the packaging tests run in the X job only), against a VTK that renders
# through OSMesa, with DISPLAY unset and no X server, the way build servers with an OSMesa (or
# EGL) VTK run them.
#
# Debian's VTK 9.1 is built for X only, so this job builds a minimal VTK 9.1 with OSMesa from
# Debian's own vtk9 source package, once, into a cache folder outside the checkout:
#   ${NORMALMAPPING_CACHE:-/var/cache/normalmapping}/vtk-9.1-osmesa
# It is reused while the key recorded there (source versions and configure options) matches,
# and rebuilt otherwise. Then the module is built against it in ${OSMESA_BUILD_DIR:-build-osmesa}
# and ctest runs its tests.
#
# The machine may be shared: every compile runs under `nice -n 19` with at most
# ${OSMESA_JOBS:-2} jobs, so interactive work and other builds come first. The tests run at
# normal priority: their timeouts assume it.
#
# Installs only Debian packages, and only those missing; enables the deb-src lines for the
# mirrors already configured when apt has no source entries yet.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$root/scripts/common.sh"
cache="${NORMALMAPPING_CACHE:-/var/cache/normalmapping}"
prefix="$cache/vtk-9.1-osmesa"
work="$cache/work"
key_file="$prefix/normalmapping-key.txt"
build="${OSMESA_BUILD_DIR:-$root/build-osmesa}"
jobs="${OSMESA_JOBS:-2}"
niced=(nice -n 19)

# libosmesa6-dev: the offscreen Mesa library VTK renders through. ninja-build, dpkg-dev: the
# VTK build and `apt-get source`. Then the third-party libraries Debian strips from VTK's
# source (VTK uses Debian's), TBB (the SMP backend of Debian's VTK, so the thread tests see
# the same behaviour), and the module's own build and test dependencies.
install_packages() {
  install_missing build-essential cmake ninja-build dpkg-dev libosmesa6-dev libtbb-dev \
    zlib1g-dev libpng-dev libjpeg-dev libtiff-dev libexpat1-dev libfreetype-dev liblz4-dev \
    liblzma-dev libdouble-conversion-dev libutfcpp-dev libeigen3-dev libjsoncpp-dev \
    libgtest-dev libbenchmark-dev libglm-dev libtinygltf-dev nlohmann-json3-dev libstb-dev
}

# The source package and version a binary package comes from, as name=version: the installed
# version when there is one, else apt's candidate ("Source: glew (2.2.0-4)" when a binary
# rebuild gave the binary another version).
source_of() {
  local version
  version="$(dpkg-query -W -f='${Version}' "$1" 2>/dev/null || true)"
  [ -n "$version" ] || version="$(apt-cache policy "$1" | awk '/Candidate:/ {print $2}')"
  apt-cache show "$1=$version" | awk -v name="$1" -v v="$version" '
    /^Source:/ {name = $2; if ($3 != "") v = substr($3, 2, length($3) - 2)}
    /^$/ {exit}
    END {print name "=" v}'
}

# add_options FORMAT NAME...: one VTK option per name, FORMAT with %s for the name.
add_options() {
  local format="$1" name option
  shift
  for name in "$@"; do
    printf -v option -- "$format" "$name"
    vtk_options+=("$option")
  done
}

# VTK's configuration: only the modules the module, its tests, benchmarks and tool need; no
# wrapping, no MPI; Debian's library for every one Debian removes from the source.
vtk_configuration() {
  vtk_options=(
    -DCMAKE_BUILD_TYPE=Release
    # -O1: this VTK only runs the tests, and compiling it is about half of a fresh machine's
    # test run; -O1 compiles in clearly less time than -O2 (Debian's level) or -O3 (CMake's).
    "-DCMAKE_C_FLAGS_RELEASE=-O1 -DNDEBUG"
    "-DCMAKE_CXX_FLAGS_RELEASE=-O1 -DNDEBUG"
    -DBUILD_SHARED_LIBS=ON
    -DCMAKE_INSTALL_LIBDIR=lib
    -DCMAKE_INSTALL_RPATH="$prefix/lib"
    -DVTK_OPENGL_HAS_OSMESA=ON
    -DVTK_USE_X=OFF
    -DVTK_DEFAULT_RENDER_WINDOW_OFFSCREEN=ON
    -DVTK_SMP_IMPLEMENTATION_TYPE=TBB
    -DVTK_BUILD_ALL_MODULES=OFF
    -DVTK_BUILD_TESTING=OFF
    -DVTK_BUILD_EXAMPLES=OFF
    -DVTK_BUILD_DOCUMENTATION=OFF
    -DVTK_ENABLE_REMOTE_MODULES=OFF
    -DVTK_WRAP_PYTHON=OFF
    -DVTK_WRAP_JAVA=OFF
    -DVTK_USE_MPI=OFF
  )
  vtk_module_options vtk_options
  # VTK's importers, for the test of vtkGLTFImporter through the object factory.
  vtk_options+=(-DVTK_MODULE_ENABLE_VTK_IOImport=YES)
  add_options "-DVTK_MODULE_USE_EXTERNAL_VTK_%s=ON" doubleconversion eigen expat freetype \
    gl2ps glew hdf5 jpeg jsoncpp libproj libxml2 lz4 lzma netcdf ogg png sqlite theora tiff \
    utf8 zlib
  # Debian's libGLEW is built for GLX; VTK needs GLEW built for OSMesa, installed in the
  # prefix. Its soname is libGLEWosmesa.so.2.2, so that it is never confused with Debian's
  # libGLEW.so.2.2 at run time; the link name libGLEW.so is what VTK's FindGLEW looks for.
  # GLEW_ROOT points FindGLEW at it, and VTK records GLEW_ROOT in its installed package
  # (vtk-find-package-helpers.cmake, written only for a non-relocatable install), so programs
  # built against this VTK find the same GLEW with no option of their own.
  vtk_options+=(-DGLEW_ROOT="$prefix" -DVTK_RELOCATABLE_INSTALL=OFF)
  vtk_source="$(source_of libvtk9-dev)"
  glew_source="$(source_of libglew-dev)"
  key="$vtk_source $glew_source GLEW:SYSTEM=linux-osmesa,NAME=GLEWosmesa ${vtk_options[*]}"
}

enable_deb_src() {
  if apt-get source --print-uris -qq vtk9 >/dev/null 2>&1; then
    return
  fi
  echo "== enabling the deb-src lines of the configured mirrors"
  local list=/etc/apt/sources.list.d/normalmapping-deb-src
  if [ -f /etc/apt/sources.list.d/debian.sources ]; then
    sed 's/^Types: deb$/Types: deb-src/' /etc/apt/sources.list.d/debian.sources |
      $sudo_cmd tee "$list.sources" >/dev/null
  else
    sed -n 's/^deb \(.*\)$/deb-src \1/p' /etc/apt/sources.list | $sudo_cmd tee "$list.list" >/dev/null
  fi
  apt_get update -qq
}

# Debian's sources in the work folder, unless those of this key are already there.
fetch_sources() {
  if [ "$(cat "$work/normalmapping-key.txt" 2>/dev/null)" = "$key" ]; then
    return
  fi
  rm -rf "$work"
  mkdir -p "$work"
  enable_deb_src
  echo "== Debian's sources: $vtk_source $glew_source"
  (cd "$work" && apt-get source -qq "$vtk_source" "$glew_source" >"$work/source.log" 2>&1) ||
    { cat "$work/source.log"; exit 1; }
  printf '%s\n' "$key" >"$work/normalmapping-key.txt"
}

build_glew() {
  echo "== GLEW for OSMesa"
  local src
  src="$(find "$work" -maxdepth 1 -type d -name 'glew-*' | head -n 1)"
  # SYSTEM=linux-osmesa resolves GL entry points through OSMesa; NAME renames the library.
  local glew_make=(make -C "$src" SYSTEM=linux-osmesa NAME=GLEWosmesa GLEW_DEST="$prefix"
    LIBDIR="$prefix/lib")
  { "${niced[@]}" "${glew_make[@]}" -j "$jobs" glew.lib.shared &&
    "${glew_make[@]}" install.include; } >"$work/glew-build.log" 2>&1 ||
    { tail -n 40 "$work/glew-build.log"; exit 1; }
  cp -a "$src"/lib/libGLEWosmesa.so.* "$prefix/lib/"
  ln -s libGLEWosmesa.so.2.2 "$prefix/lib/libGLEW.so"
}

# GLEW and VTK into the prefix. The sources and VTK's build tree stay in the work folder until
# VTK is installed, so an interrupted build resumes where it stopped when run again.
build_vtk() {
  fetch_sources
  rm -rf "$prefix"
  mkdir -p "$prefix/lib"
  build_glew
  echo "== VTK with OSMesa (minimal), into $prefix"
  local src
  src="$(find "$work" -maxdepth 1 -type d -name 'vtk9-*' | head -n 1)"
  install_vtk "$src" "$work/vtk-build" "$prefix" "$work/vtk" "$jobs" "${vtk_options[@]}"
  printf '%s\n' "$key" >"$key_file"
  rm -rf "$work"
}

# Every test with no way to X: no program links libX11, DISPLAY is unset, and an Xvfb that
# refuses to start comes first on PATH, so a test that took the X path fails instead of
# quietly starting a server. Then the render window classes the tests printed: all OSMesa's.
run_tests() {
  local program
  for program in "$build"/bin/*; do
    if ldd "$program" 2>/dev/null | grep -q "libX11"; then
      echo "$program loads libX11: it does not build for this VTK without X" >&2
      exit 1
    fi
  done
  unset DISPLAY WAYLAND_DISPLAY XAUTHORITY
  local guard
  guard="$(mktemp -d)"
  printf '#!/bin/sh\necho "Xvfb called in the OSMesa job: a test took the X path" >&2\nexit 1\n' \
    >"$guard/Xvfb"
  chmod +x "$guard/Xvfb"
  # Every test but the packaging tests, which configure and compile the sources again in
  # nested projects: they check the CMake packaging, which does not depend on how VTK renders,
  # and the X job runs them.
  echo "== every test but the packaging tests, with DISPLAY unset and no X server"
  local status=0
  (cd "$build" && PATH="$guard:$PATH" ctest --output-on-failure -j "$jobs" \
    -LE '^packaging$') || status=$?
  rm -rf "$guard"

  # LastTest.log holds every test's output, passed or failed.
  local paths
  paths="$(grep -hi "rendering path" "$build/Testing/Temporary/LastTest.log" | sort | uniq -c)" ||
    true
  echo "== rendering paths the tests printed (count, line):"
  echo "${paths:-  none}"
  if [ -z "$paths" ] || echo "$paths" | grep -vq "vtkOSOpenGLRenderWindow"; then
    echo "== not every rendering test went through vtkOSOpenGLRenderWindow" >&2
    status=1
  fi
  return "$status"
}

main() {
  install_packages
  vtk_configuration
  ensure_writable_dir "$cache"
  # One job at a time builds or uses the cache.
  exec 9>"$cache/osmesa.lock"
  flock 9
  if [ "$(cat "$key_file" 2>/dev/null)" = "$key" ]; then
    echo "== reusing the OSMesa VTK in $prefix"
  else
    build_vtk
  fi
  echo "== the module against the OSMesa VTK, in $build"
  build_module "$prefix/lib/cmake/vtk-9.1" "$build" "$jobs" -DNORMALMAPPING_WARNINGS_AS_ERRORS=ON
  run_tests
}

# One line: bash reads it whole before main starts, so editing this file while a job runs does
# not change what that job does.
main "$@"; exit
