#!/bin/sh
# Takes docs/img/blender_*.png: Blender's UI with the add-on, under xvfb
# (docs/img/blender_screenshots.py says what each shows).
#   docs/img/blender_screenshots.sh [BUILD] [OUTDIR]
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:-$here/../../build}" && pwd)
out=$(cd "${2:-$here}" && pwd)
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
export SHAFTS_ADDON_ZIP="$build/shafts_blender.zip" \
  BLENDER_USER_SCRIPTS="$scratch/scripts" BLENDER_USER_CONFIG="$scratch/config"
mkdir -p "$BLENDER_USER_SCRIPTS/addons" "$BLENDER_USER_CONFIG"
blender -b --factory-startup --python-exit-code 1 \
  --python "$here/blender_screenshots.py" -- prepare "$scratch/scene.blend"
xvfb-run -a -s "-screen 0 1280x720x24" blender --factory-startup "$scratch/scene.blend" \
  --python "$here/blender_screenshots.py" -- shoot "$out"
# 1280x720 screenshots are 350-450 KB; at 75% they stay legible and small.
for png in "$out"/blender_*_viewport.png "$out"/blender_*_render.png; do
  oiiotool "$png" --resize 75% -o "$png"
done
