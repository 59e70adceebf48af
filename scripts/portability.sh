#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Compiles the module library's sources for 64-bit ARM with Debian's cross compiler
# (g++-aarch64-linux-gnu), against VTK's headers:
#   bash scripts/portability.sh [BUILD]
# The library must build for any CPU VTK supports; this proves that nothing in it is x86-only.
# It reuses the compile commands of an x86 build (BUILD, default ./build, configured with
# CMAKE_EXPORT_COMPILE_COMMANDS=ON), so the flags, definitions and include paths are the real
# ones, with the compiler swapped. Object files only: nothing is linked, nothing is run.
# (The clang build of the same sources is scripts/sanitize.sh.)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="$(cd "${1:-${BUILD_DIR:-$root/build}}" && pwd)"
compiler=aarch64-linux-gnu-g++
if ! command -v "$compiler" >/dev/null; then
  echo "$compiler is missing (Debian package g++-aarch64-linux-gnu)" >&2
  exit 1
fi
if [ ! -f "$build/compile_commands.json" ]; then
  echo "$build/compile_commands.json is missing: configure with -DCMAKE_EXPORT_COMPILE_COMMANDS=ON" >&2
  exit 1
fi
out="$build/portability-aarch64"
rm -rf "$out"
mkdir -p "$out"

# One line per library source: the x86 command's arguments with the compiler and the output
# replaced. The library's sources are those compiled into its object files (CMakeFiles/NormalMapping).
python3 - "$build/compile_commands.json" "$out" "$compiler" >"$out/commands.txt" <<'EOF'
import json, os, shlex, sys
commands, out, compiler = sys.argv[1], sys.argv[2], sys.argv[3]
for entry in json.load(open(commands)):
    args = entry.get("arguments") or shlex.split(entry["command"])
    if "-o" not in args or "CMakeFiles/NormalMapping.dir" not in args[args.index("-o") + 1]:
        continue
    obj = os.path.join(out, os.path.basename(entry["file"]) + ".o")
    args = [compiler] + args[1:]
    args[args.index("-o") + 1] = obj
    print(entry["directory"] + "\t" + shlex.join(args))
EOF
count=$(wc -l <"$out/commands.txt")
if [ "$count" -eq 0 ]; then
  echo "no library sources found in $build/compile_commands.json" >&2
  exit 1
fi
failed=0
while IFS=$'\t' read -r dir cmd; do
  if ! (cd "$dir" && eval "$cmd") >"$out/log.txt" 2>&1; then
    echo "aarch64 compile failed: ${cmd##* }" >&2
    cat "$out/log.txt" >&2
    failed=$((failed + 1))
  fi
done <"$out/commands.txt"
objects=$(find "$out" -name '*.o' | wc -l)
machines=$(find "$out" -name '*.o' -exec readelf -h {} \; | grep -c "Machine: *AArch64" || true)
echo "aarch64: $objects of $count library sources compiled ($machines of them AArch64 objects), $failed failed"
[ "$failed" -eq 0 ] && [ "$machines" -eq "$count" ]
