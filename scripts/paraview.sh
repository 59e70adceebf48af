#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Build the ParaView plugin (ParaView/) against Debian's ParaView 5.11 and run its tests:
#   bash scripts/paraview.sh [test]     # install what is missing, build, run the pvbatch tests
#   bash scripts/paraview.sh build      # install what is missing and build
#   bash scripts/paraview.sh gui        # open ParaView with the plugin loaded
#   bash scripts/paraview.sh screenshot # docs/paraview.png: the GUI under Xvfb, the plugin loaded
# Installs only Debian packages, and only those missing. BUILD_DIR overrides ./build-paraview;
# NORMALMAP_TOOL names the normalmap tool whose .vtm output a test opens (default: ./build's).
#
# ParaView ships its own VTK (9.2, libvtk*-pv5.11.so) whose symbols clash with Debian's VTK 9.1,
# so the plugin compiles VTK::NormalMapping again against ParaView's VTK. ParaView's CMake package
# also needs python3-paraview, which conflicts with python3-vtk9 (the project's Python tests): the
# package is unpacked, not installed, into a private prefix (see make_prefix) that the plugin
# build and its tests alone see. The system's VTK and Python packages stay as they are.
set -euo pipefail
job="${1:-test}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
source "$root/scripts/common.sh"
build="${BUILD_DIR:-$root/build-paraview}"
prefix="$build/prefix"

packages=(build-essential cmake libglm-dev xvfb xauth paraview paraview-dev openmpi-bin
  qtbase5-dev libqt5opengl5-dev libqt5svg5-dev qttools5-dev qtxmlpatterns5-dev-tools)
install_missing "${packages[@]}"

multiarch="$(gcc -dumpmachine)" # after the install: build-essential brings gcc

# A prefix that looks like /usr to ParaView's relocatable CMake package (which finds everything
# relative to its own folder), made of links to /usr plus the unpacked python3-paraview: its
# Python package (pvpython, pvbatch and the CMake package's Python targets need it), its
# wrapping hierarchy files and pvpython. Remade when the installed ParaView changes.
make_prefix() {
  local version deb
  version="$(dpkg-query -W -f='${Version}' paraview)"
  [ "$(cat "$prefix/.version" 2>/dev/null)" = "$version" ] && return 0
  rm -rf "$prefix" "$build/deb"
  mkdir -p "$build/deb" "$prefix/bin" "$prefix/lib/$multiarch/cmake" \
    "$prefix/lib/$multiarch/vtk/hierarchy" "$prefix/lib/python3"
  (cd "$build/deb" && apt-get download -qq "python3-paraview=$version" 2>/dev/null) || {
    $sudo_cmd apt-get update -qq
    (cd "$build/deb" && apt-get download -qq "python3-paraview=$version")
  }
  deb="$(ls "$build"/deb/python3-paraview_*.deb)"
  dpkg-deb -x "$deb" "$build/deb/root"
  rm -f "$deb"
  local unpacked="$build/deb/root/usr"
  ln -s /usr/include "$prefix/include"
  ln -s /usr/share "$prefix/share"
  ln -s /usr/bin/* "$prefix/bin/"
  ln -sf "$unpacked"/bin/pvpython* "$prefix/bin/"
  local entry
  for entry in /usr/lib/"$multiarch"/*; do
    case "${entry##*/}" in
      cmake | vtk) ;;
      *) ln -s "$entry" "$prefix/lib/$multiarch/" ;;
    esac
  done
  # A tree of links (real folders), so that the package's own folder is inside the prefix.
  cp -rs "/usr/lib/$multiarch/cmake/paraview-5.11" "$prefix/lib/$multiarch/cmake/"
  ln -s "$unpacked/lib/$multiarch/vtk/hierarchy/ParaView" "$prefix/lib/$multiarch/vtk/hierarchy/"
  ln -s "$unpacked/lib/python3/dist-packages" "$prefix/lib/python3/"
  echo "$version" >"$prefix/.version"
}
make_prefix

# The normalmap tool of the project's build (NORMALMAP_TOOL, else ./build's), which a test runs.
tool="${NORMALMAP_TOOL:-$root/build/bin/normalmap}"
# Configured every time (about a second once the cache exists), so that a build made with other
# settings gets these.
configure_and_build() {
  cmake -S "$root/ParaView" -B "$build" -DCMAKE_BUILD_TYPE=Release \
    -DParaView_DIR="$prefix/lib/$multiarch/cmake/paraview-5.11" \
    -DNORMALMAPPING_TOOL="$tool" -DNORMALMAPPING_WARNINGS_AS_ERRORS=ON \
    >"$build/configure.log" 2>&1 ||
    { cat "$build/configure.log"; exit 1; }
  cmake --build "$build" -j 2 >"$build/build.log" 2>&1 ||
    { grep -E "error|Error" "$build/build.log"; exit 1; }
}
configure_and_build

plugin="$build/lib/paraview-5.11/plugins/NormalMappingPlugin/NormalMappingPlugin.so"
export PYTHONPATH="$prefix/lib/python3/dist-packages"
case "$job" in
  build) ;;
  test)
    (cd "$build" && ctest --output-on-failure -j 2)
    ;;
  gui)
    PV_PLUGIN_PATH="${plugin%/*}" paraview
    ;;
  screenshot)
    # ImageMagick's import grabs the X screen: only this job needs it.
    dpkg-query -W -f='${Status}' imagemagick 2>/dev/null | grep -q "install ok installed" ||
      DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends \
        imagemagick >"$build/apt.log" 2>&1 || { cat "$build/apt.log"; exit 1; }
    work="$build/screenshot"
    rm -rf "$work" && mkdir -p "$work/config/ParaView"
    # Settings of its own (the user's are not read or written): no welcome dialog.
    printf '[General]\nGeneralSettings.ShowWelcomeDialog=0\n' \
      >"$work/config/ParaView/ParaView5.11.0.ini"
    XDG_CONFIG_HOME="$work/config" NORMALMAPPING_WORK="$work" PV_PLUGIN_PATH="${plugin%/*}" \
      PYTHONPATH="$PYTHONPATH:$root/ParaView/Testing" \
      "$root/Testing/Rendering/RunHeadless.sh" xvfb sh -c '
        paraview -geometry 1280x1000+0+0 --script="$1/ParaView/Testing/GuiScreenshot.py" \
          >"$2/paraview.log" 2>&1 &
        gui=$!
        tries=0
        while [ ! -e "$2/ready" ] && [ "$tries" -lt 600 ]; do sleep 0.1; tries=$((tries + 1)); done
        sleep 3 # the window draws after the script returns
        import -window "ParaView 5.11.0" "$1/docs/paraview.png"
        kill "$gui"' sh "$root" "$work"
    echo "== wrote $root/docs/paraview.png"
    ;;
  *)
    echo "usage: $0 test|build|gui|screenshot" >&2
    exit 2
    ;;
esac
