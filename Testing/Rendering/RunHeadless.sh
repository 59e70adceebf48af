#!/bin/sh
# Run one rendering test headless, on Mesa's llvmpipe software rasterizer:
#   RunHeadless.sh osmesa|xvfb <command...>
# osmesa: VTK renders offscreen through OSMesa, no X server at all.
# xvfb:   VTK needs an X display (Debian's VTK has no OSMesa or EGL): a private Xvfb server.
#         Xvfb picks a free display number itself (-displayfd), so tests can run in parallel
#         without racing for display numbers (xvfb-run -a does race under load). -noreset:
#         by default the server resets whenever its last client leaves, and a test that closes
#         one window before opening the next can connect during that reset and fail.
mode="$1"
shift
export LIBGL_ALWAYS_SOFTWARE=1
export GALLIUM_DRIVER=llvmpipe
if [ "$mode" = osmesa ]; then
  export NORMALMAPPING_HEADLESS_PATH="OSMesa, no X server"
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
kill "$server" 2>/dev/null
wait "$server" 2>/dev/null
rm -rf "$work"
exit "$status"
