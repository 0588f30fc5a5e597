#!/bin/sh
# Runs blender_addon/engines_bench.py in Blender (background mode) with the
# add-on installed from the build's zip into a scratch user scripts folder.
#   blender_addon/engines_bench.sh [BUILD]
here=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:-$here/../build}" && pwd)
SHAFTS_ADDON_ZIP="$build/shafts_blender.zip" SHAFTS_BUILD="$build" \
  exec "$here/run_blender_test.sh" "$here/engines_bench.py"
