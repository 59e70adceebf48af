#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Runs the benchmark set and writes docs/benchmarks.md and docs/benchmarks.png:
#   bash scripts/bench.sh [--smoke] [--out DIR] [--build DIR] [--headless offscreen|xvfb]
# `bash scripts/bootstrap.sh bench` builds the project and runs this. The programs are in
# BUILD/bin (--build, else $BUILD_DIR, else ./build):
#   BenchTangentAccuracy     filter accuracy (analytic tangents, MikkTSpace reference meshes)
#   BenchTangentFrames       filter throughput and peak memory (Google Benchmark); then, with
#                            --build-variant, the default method against VTK's filter from this
#                            build and (not with --smoke) from two more, each configured and built
#                            here under BUILD/variants: with Clang 14, and without function
#                            multiversioning (-DNORMALMAPPING_MULTIVERSIONING=OFF)
#   BenchMikkTSpace          MikkTSpace against the original mikktspace.c, paired runs; only when
#                            the build has the original's source (MIKKTSPACE_REFERENCE_DIR of
#                            bootstrap.sh, or CMake's NORMALMAPPING_MIKKTSPACE_REFERENCE_DIR), else
#                            its section says that it was not run and how to run it
#   BenchNormalMapRendering  frame time, image error and vertex memory of the mappers (llvmpipe)
#   BenchChart               the speed-versus-accuracy chart (VTK charts); a build against a VTK
#                            without them has no BenchChart, and benchmarks.md then says that
#                            there is no chart
# Each writes its section (and a tab-separated table) into a work folder (BUILD/bench, or the --out
# folder with --smoke), with its console output in <name>.log; this script adds the header
# (machine, load, versions, date, run time) and writes benchmarks.md and benchmarks.png into
# --out (default: docs/). --smoke: tiny meshes and few repetitions, only to check that
# everything runs (ctest BenchmarkSmoke); its numbers mean nothing.
# The rendering programs run headless (Testing/Rendering/RunHeadless.sh): exit status 125 when
# that is impossible (no Xvfb), 1 when a program fails. --headless: the way the build's VTK
# renders (ctest BenchmarkSmoke passes the build's own); without it, that of the VTK in
# /usr/include (Debian's: xvfb).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${BUILD_DIR:-$root/build}"
out="$root/docs"
smoke=()
mode=""
while [ $# -gt 0 ]; do
  case "$1" in
    --smoke) smoke=(--smoke) ;;
    --out) out="$2"; shift ;;
    --build) build="$2"; shift ;;
    --headless) mode="$2"; shift ;;
    *) echo "usage: $0 [--smoke] [--out DIR] [--build DIR] [--headless offscreen|xvfb]" >&2; exit 2 ;;
  esac
  shift
done
bin="$build/bin"
for program in BenchTangentAccuracy BenchTangentFrames BenchMikkTSpace BenchNormalMapRendering; do
  if [ ! -x "$bin/$program" ]; then
    echo "$bin/$program is missing: build first (bash scripts/bootstrap.sh bench does)" >&2
    exit 1
  fi
done
work="$build/bench"
[ "${#smoke[@]}" -eq 0 ] || work="$out"
mkdir -p "$work" "$out"
rm -f "$work"/{filter,mikktspace,accuracy,rendering}.{md,tsv,env,log} "$work/benchmarks.png" \
  "$work"/variant*.{md,log}

# Debian's VTK renders through X only: a private Xvfb; a VTK without X (OSMesa, EGL) needs none.
if [ -z "$mode" ]; then
  mode=offscreen
  if grep -qs "^#define VTK_USE_X" /usr/include/vtk-*/vtkRenderingOpenGLConfigure.h; then
    mode=xvfb
  fi
fi

start=$(date +%s)
load_start="$(cut -d' ' -f1-3 /proc/loadavg)"
timings=()
# run NAME COMMAND...: runs a program with its output in $work/NAME.log, and times it.
run() {
  local name="$1" t0 status=0
  shift
  t0=$(date +%s)
  echo "== $name: $*"
  "$@" >"$work/$name.log" 2>&1 || status=$?
  if [ "$status" -eq 125 ]; then
    grep -h "SKIPPED" "$work/$name.log" || true
    exit 125
  fi
  if [ "$status" -ne 0 ]; then
    echo "$name failed (exit status $status); the end of $work/$name.log:" >&2
    tail -n 30 "$work/$name.log" >&2
    exit 1
  fi
  timings+=("$name $(($(date +%s) - t0)) s")
}
headless="$root/Testing/Rendering/RunHeadless.sh"
run accuracy "$bin/BenchTangentAccuracy" --out "$work" "${smoke[@]}"
run filter "$bin/BenchTangentFrames" --out "$work" "${smoke[@]}"
run variant "$bin/BenchTangentFrames" --build-variant --out "$work" "${smoke[@]}"
missing=()
if [ "${#smoke[@]}" -eq 0 ]; then
  for variant in "clang:-DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14" \
    "portable:-DNORMALMAPPING_MULTIVERSIONING=OFF"; do
    name="${variant%%:*}"
    read -r -a flags <<<"${variant#*:}"
    if [ "$name" = clang ] && ! command -v clang++-14 >/dev/null; then
      missing+=("No Clang row: clang++-14 is not installed (\`bash scripts/bootstrap.sh bench\` installs it).")
      continue
    fi
    dir="$build/variants/$name"
    run "variant-build-$name" bash -c 'cmake -S "$1" -B "$2" -DCMAKE_BUILD_TYPE=Release "${@:3}" &&
      cmake --build "$2" -j "$(nproc)" --target BenchTangentFrames' _ "$root" "$dir" "${flags[@]}"
    run "variant-$name" "$dir/bin/BenchTangentFrames" --build-variant --out "$work"
  done
fi
run mikktspace "$bin/BenchMikkTSpace" --out "$work" "${smoke[@]}"
run rendering "$headless" "$mode" "$bin/BenchNormalMapRendering" --out "$work" "${smoke[@]}"
chart=no
if [ -x "$bin/BenchChart" ]; then
  run chart "$headless" "$mode" "$bin/BenchChart" --out "$work"
  chart=yes
fi
load_end="$(cut -d' ' -f1-3 /proc/loadavg)"
seconds=$(($(date +%s) - start))

cpu="$(grep -m1 "model name" /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')"
memory="$(awk '/MemTotal/ {printf "%.0f", $2 / 1048576}' /proc/meminfo)"
command="bash scripts/bench.sh${smoke[*]:+ ${smoke[*]}}"
parts="$(printf '%s, ' "${timings[@]}")"
{
  echo "# Benchmarks"
  echo
  if [ "${#smoke[@]}" -gt 0 ]; then
    echo "**Smoke run** (tiny meshes, few repetitions: it only shows that everything runs; the"
    echo "numbers mean nothing)."
    echo
  fi
  echo "Written by \`$command\` (what \`bash scripts/bootstrap.sh bench\` runs after building);"
  echo "do not edit by hand. $(date -u '+%Y-%m-%d'); the whole run took $seconds s"
  echo "(${parts%, })."
  echo
  echo "- Machine: ${cpu:-unknown CPU}, $(nproc) cores, $memory GiB of memory, $(uname -sr)."
  echo "- Load average (1, 5, 15 minutes): $load_start at the start, $load_end at the end."
  echo "  Other work may have been running on the machine: absolute figures move with it; the"
  echo "  ratios compare runs in the same process, interleaved, and move less."
  echo "- $(cat "$work/filter.env"); $(cat "$work/rendering.env")."
  echo
  if [ "$chart" = yes ]; then
    echo "![Speed versus accuracy: the tangent filters (left) and the mappers (right), each point"
    echo "labelled, the Pareto front dashed](benchmarks.png)"
    echo
    echo "Left: each tangent filter's throughput (float torus nearest to a million triangles, one"
    echo "thread) against its mean angle to the analytic tangent on the wavy surface (middle"
    echo "resolution); the dotted line is the floor. Right: each mapper configuration's time per"
    echo "frame against its mean error from the displaced geometry. Both axes are logarithmic;"
    echo "lower is better, and so is further right on the left (faster) and further left on the"
    echo "right (less time). The dashed lines join the points that no other point beats on both"
    echo "(on the right, one line per lighting model: their errors have different references)."
  else
    echo "No chart: this build's VTK has no 2D charts (ChartsCore), so BenchChart was not built."
  fi
  echo
  cat "$work/filter.md" "$work/variants.md"
  echo # the rows of variants.md come from several programs: none ends the section
  for line in "${missing[@]}"; do
    echo "$line"
    echo
  done
  cat "$work/mikktspace.md" "$work/accuracy.md" "$work/rendering.md"
} >"$work/benchmarks.md.new"
mv "$work/benchmarks.md.new" "$out/benchmarks.md"
written="$out/benchmarks.md"
if [ "$chart" = yes ]; then
  [ "$work/benchmarks.png" -ef "$out/benchmarks.png" ] ||
    cp "$work/benchmarks.png" "$out/benchmarks.png"
  written="$written and $out/benchmarks.png"
fi
echo "== wrote $written in $seconds s (logs in $work)"
