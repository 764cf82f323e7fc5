#!/usr/bin/env bash
# Regenerates the pictures in docs/images from the current build:
#   default.png      the README's picture: the built-in default scene as `gridrt` renders it
#                    (Readme.DefaultPictureIsWhatTheProgramRenders compares it pixel for pixel)
#   pe_bunny.png     bunny_res4's winning PE per pixel, false colour
#   tests_bunny.png  its ray-triangle tests per primary ray, false colour
# The heat maps need the benchmark's Python packages (tools/setup.sh --bench makes .venv).
# The `tests` AOV depends on the rays and the structure alone (the PEs up to each ray's
# winner, host/gridrt/ray_tests.h): the same on any number of threads.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "${1:-}" = "--help" ] || [ "${1:-}" = "-h" ]; then
  sed -n '2,9p' "$0" | sed 's/^# \{0,1\}//'
  exit 0
fi
build/gridrt -q -o docs/images/default.png
if [ -x .venv/bin/python ]; then
  tmp=$(mktemp -d)
  trap 'rm -rf "$tmp"' EXIT
  build/gridrt scenes/models/bunny_res4.glb -q --width 320 --height 240 \
    --primary-only -o "$tmp/bunny.exr" --aov pe="$tmp/pe.exr" --aov tests="$tmp/tests.exr"
  .venv/bin/python tools/heatmap.py "$tmp/pe.exr" docs/images/pe_bunny.png
  .venv/bin/python tools/heatmap.py "$tmp/tests.exr" docs/images/tests_bunny.png
else
  echo "make_readme_images: no .venv (tools/setup.sh --bench): heat maps left as they are" >&2
fi
echo "make_readme_images: docs/images updated"
