# SPDX-License-Identifier: BSD-3-Clause
# What the scripts share; each sources this file.

# sudo for the commands that need root, when not root already.
sudo_cmd=""
[ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"

# apt-get as root, waiting up to 10 minutes for another apt to release its lock.
apt_get() {
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get -o DPkg::Lock::Timeout=600 "$@"
}

# install_missing PACKAGE...: installs from Debian those of the packages that are not installed,
# without recommends; apt's output is shown only when it fails.
install_missing() {
  local missing=() p log
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" ||
      missing+=("$p")
  done
  [ "${#missing[@]}" -gt 0 ] || return 0
  echo "== installing missing Debian packages: ${missing[*]}"
  log="$(mktemp)"
  { apt_get update -qq && apt_get install -y -qq --no-install-recommends "${missing[@]}"; } \
    >"$log" 2>&1 || { cat "$log"; rm -f "$log"; return 1; }
  rm -f "$log"
}

# vtk_module_options ARRAY: appends to the bash array named ARRAY the VTK configure options of
# the jobs that build a VTK of their own (osmesa.sh, newvtk.sh): the modules the module, its
# tests and its tool need, every other group left out. Not VTK's 2D charts either: only the
# benchmark chart (BenchChart) needs them, and with what they pull in they are a tenth of a
# minimal VTK build (the benchmark smoke test then checks its tables without the chart).
vtk_module_options() {
  local -n _out="$1"
  local name
  for name in Imaging MPI Qt Rendering StandAlone Views Web; do
    _out+=("-DVTK_GROUP_ENABLE_$name=DONT_WANT")
  done
  for name in CommonCore CommonDataModel CommonExecutionModel CommonMath CommonSystem \
    CommonComputationalGeometry FiltersCore FiltersGeneral FiltersSources FiltersTexture \
    ImagingCore IOGeometry IOImage IOLegacy IOPLY IOXML RenderingCore RenderingOpenGL2 \
    RenderingFreeType RenderingUI TestingRendering; do
    _out+=("-DVTK_MODULE_ENABLE_VTK_$name=YES")
  done
}

# ensure_writable_dir DIR: creates DIR, owned by the caller (through sudo when needed).
ensure_writable_dir() {
  if ! mkdir -p "$1" 2>/dev/null || [ ! -w "$1" ]; then
    $sudo_cmd mkdir -p "$1"
    $sudo_cmd chown "$(id -u):$(id -g)" "$1"
  fi
}

# install_vtk SOURCE BUILD PREFIX LOGS JOBS OPTION...: configures the VTK source tree SOURCE in
# BUILD (Ninja, the options, installing into PREFIX), builds it with JOBS jobs under nice and
# installs it; the logs are LOGS-configure.log and LOGS-build.log, shown in part on failure.
# Not through ccache: each VTK is built once per cache key, so its objects would only fill the
# compiler cache (bootstrap.sh).
install_vtk() {
  local source="$1" build="$2" prefix="$3" logs="$4" jobs="$5"
  shift 5
  env -u CMAKE_C_COMPILER_LAUNCHER -u CMAKE_CXX_COMPILER_LAUNCHER \
    cmake -S "$source" -B "$build" -G Ninja --no-warn-unused-cli \
    -DCMAKE_INSTALL_PREFIX="$prefix" "$@" >"$logs-configure.log" ||
    { tail -n 40 "$logs-configure.log"; return 1; }
  nice -n 19 cmake --build "$build" -j "$jobs" >"$logs-build.log" 2>&1 ||
    { grep -E "error|FAILED" "$logs-build.log" | head -n 40; return 1; }
  cmake --install "$build" >/dev/null
}

# build_module VTK_DIR BUILD JOBS OPTION...: configures the module (the checkout at $root)
# against the VTK package in VTK_DIR, without Python wrapping, in BUILD, with the options, and
# builds it with JOBS jobs under nice, showing only the compiler's errors and warnings.
build_module() {
  local vtk_dir="$1" build="$2" jobs="$3"
  shift 3
  cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DVTK_DIR="$vtk_dir" \
    -DNORMALMAPPING_WRAP_PYTHON=OFF "$@" >/dev/null
  nice -n 19 cmake --build "$build" -j "$jobs" 2>&1 | grep -E "error|warning: |Error" || true
  nice -n 19 cmake --build "$build" -j "$jobs" >/dev/null
}
