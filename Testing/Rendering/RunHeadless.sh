#!/bin/sh
# SPDX-License-Identifier: BSD-3-Clause
# Run one rendering test headless, on Mesa's llvmpipe software rasterizer:
#   RunHeadless.sh offscreen|xvfb <command...>
# offscreen: VTK is built without X (OSMesa or EGL) and renders with no X server at all.
# xvfb:      VTK is built with X (Debian's): it needs a display even offscreen, so the command
#            gets a private Xvfb server.
#         Xvfb picks a free display number itself (-displayfd), so tests can run in parallel
#         without racing for display numbers (xvfb-run -a does race under load). -noreset:
#         by default the server resets whenever its last client leaves, and a test that closes
#         one window before opening the next can connect during that reset and fail.
mode="$1"
shift
export LIBGL_ALWAYS_SOFTWARE=1
export GALLIUM_DRIVER=llvmpipe
if [ "$mode" = offscreen ]; then
  unset DISPLAY
  export NORMALMAPPING_HEADLESS_PATH="no X server"
  exec "$@"
fi
if ! command -v Xvfb >/dev/null 2>&1; then
  echo "SKIPPED: this VTK needs an X display and Xvfb is not installed (Debian package: xvfb)"
  exit 125
fi
work="$(mktemp -d)"
Xvfb -displayfd 3 -screen 0 1280x1024x24 -nolisten tcp -ac -noreset 3>"$work/display" 2>"$work/log" &
server=$!
tries=0
while [ ! -s "$work/display" ] && [ "$tries" -lt 300 ]; do
  sleep 0.1
  tries=$((tries + 1))
done
if [ ! -s "$work/display" ]; then
  echo "Xvfb did not start:"
  cat "$work/log"
  kill "$server" 2>/dev/null
  rm -rf "$work"
  exit 1
fi
export DISPLAY=":$(cat "$work/display")"
export NORMALMAPPING_HEADLESS_PATH="Xvfb $DISPLAY, Mesa llvmpipe"
"$@"
status=$?
# On a failure, what the server says, and whether it went away during the test (a client then
# dies with an X I/O error that says nothing of the cause).
if [ "$status" -ne 0 ]; then
  if ! kill -0 "$server" 2>/dev/null; then
    echo "RunHeadless: the Xvfb server on $DISPLAY exited during the test"
  fi
  if [ -s "$work/log" ]; then
    echo "RunHeadless: the Xvfb server's log:"
    cat "$work/log"
  fi
fi
kill "$server" 2>/dev/null
wait "$server" 2>/dev/null
rm -rf "$work"
exit "$status"
