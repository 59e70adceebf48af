#!/bin/sh
# Run one rendering test headless, on Mesa's llvmpipe software rasterizer:
#   RunHeadless.sh osmesa|xvfb <command...>
# osmesa: VTK renders offscreen through OSMesa, no X server at all.
# xvfb:   VTK needs an X display (Debian's VTK has no OSMesa or EGL): a private Xvfb server.
mode="$1"
shift
export LIBGL_ALWAYS_SOFTWARE=1
export GALLIUM_DRIVER=llvmpipe
if [ "$mode" = osmesa ]; then
  export NORMALMAPPING_HEADLESS_PATH="OSMesa, no X server"
  exec "$@"
fi
if ! command -v xvfb-run >/dev/null 2>&1; then
  echo "SKIPPED: this VTK needs an X display and xvfb-run is not installed (Debian: xvfb xauth)"
  exit 125
fi
export NORMALMAPPING_HEADLESS_PATH="Xvfb (xvfb-run), Mesa llvmpipe"
exec xvfb-run -a -s "-screen 0 1280x1024x24 -nolisten tcp" "$@"
