#!/bin/sh
# Runs one of the add-on's tests inside Blender, as a user's Blender would
# have it: a fresh user scripts folder (BLENDER_USER_SCRIPTS) in a scratch
# directory, factory settings, background mode. The test script finds the
# zip and the build in SHAFTS_ADDON_ZIP and SHAFTS_BUILD, and the scratch
# directory in SHAFTS_SCRATCH (kept when the test fails, for its images).
#   run_blender_test.sh TEST.py [ARGS...]
set -u
test_script=$1
shift
: "${SHAFTS_BLENDER:=blender}"
[ -f "${SHAFTS_ADDON_ZIP:-}" ] || { echo "no add-on zip: ${SHAFTS_ADDON_ZIP:-}" >&2; exit 1; }
scratch=$(mktemp -d "${TMPDIR:-/tmp}/shafts_blender_test.XXXXXX")
export SHAFTS_SCRATCH="$scratch" BLENDER_USER_SCRIPTS="$scratch/scripts" \
  BLENDER_USER_CONFIG="$scratch/config"
mkdir -p "$BLENDER_USER_SCRIPTS/addons" "$BLENDER_USER_CONFIG"
"$SHAFTS_BLENDER" -b --factory-startup --python-exit-code 1 \
  --python "$test_script" -- "$@"
status=$?
if [ "$status" -eq 0 ] || [ "$status" -eq 77 ]; then
  rm -rf "$scratch"
else
  echo "run_blender_test: kept $scratch" >&2
fi
exit "$status"
