#!/usr/bin/env bash
# Command-line behaviour of lmm_tracer: help, bad arguments and bad scenes
# exit with status 2 and write nothing, a good render writes every output and
# a statistics file, and the same command gives the same image.
set -u
tool=$1
. "$(dirname "$0")/../tools/cli_test_lib.sh"

"$tool" --help >"$dir/help" 2>&1; check "--help" 0 $?
grep -q "usage: lmm_tracer" "$dir/help" || { echo "FAIL: --help text"; fail=1; }

basic_scene "$dir/good.json" 16 12 "$POINT_LIGHT"

"$tool" "$dir/good.json" >/dev/null 2>&1; check "missing -o" 2 $?
"$tool" "$dir/good.json" -o "$dir/x.tga" >/dev/null 2>&1; check "bad extension" 2 $?
"$tool" "$dir/good.json" -o "$dir/x.exr" --spp 0 >/dev/null 2>&1; check "--spp 0" 2 $?
"$tool" "$dir/good.json" -o "$dir/x.exr" --bogus >/dev/null 2>&1; check "unknown option" 2 $?
"$tool" "$dir/good.json" -o "$dir/x.exr" --mode nonsense >/dev/null 2>&1; check "bad mode" 2 $?
bad_scenes_refused "$tool" "$dir/good.json"
camera_at_light_warns "$tool"
# Height fog renders in the reference mode (issue 12): a finite image.
height_fog_scene "$dir/good.json" "$dir/fog.json"
"$tool" "$dir/fog.json" -o "$dir/fog.exr" --spp 2 -q; check "height fog" 0 $?
[ -s "$dir/fog.exr" ] || { echo "FAIL: height fog: no image"; fail=1; }
rm -f "$dir/fog.json" "$dir/fog.exr"

"$tool" "$dir/good.json" -o "$dir/a.exr" -o "$dir/a.png" --stats "$dir/a.json" \
  --spp 4 -q; check "good render" 0 $?
for f in a.exr a.png a.json; do
  [ -s "$dir/$f" ] || { echo "FAIL: $f not written"; fail=1; }
done
grep -q '"medium_samples"' "$dir/a.json" || { echo "FAIL: stats keys"; fail=1; }
"$tool" "$dir/good.json" -o "$dir/b.exr" --spp 4 --threads 1 -q
render_cli_common "$tool" "$dir/good.json" --spp 2
render_files_distinct "$tool" "$dir/good.json" --spp 2
# Half a million samples a pixel: seconds, so the signals come mid-render.
render_signals "$tool" "$dir/good.json" --spp 500000
"$tool" "$dir/good.json" -o "$dir/x.exr" --refined -q 2>"$dir/err"; check "--refined without lmm" 2 $?
# Options that do not apply are refused, named as on the command line.
refused() { # expected message, arguments...
  local want=$1
  shift
  "$tool" "$dir/good.json" -o "$dir/x.exr" -q "$@" 2>"$dir/err"; check "$*" 2 $?
  message_has "$*" "$dir/err" "lmm_tracer: error: $want"
}
refused "--refined needs --mode lmm and --scheme refract-both" --refined
refused "--refined needs --scheme refract-both (render.scheme or the default gives refract-trace)" --mode lmm --refined
refused "--area-radius needs --mode whitted" --area-radius 0.2
refused "--caustic-rays needs --mode lmm and --scheme refract-both" --mode lmm --scheme straight --caustic-rays 5
refused "--mesh-step needs --mode lmm" --mode whitted --mesh-step 0.1
refused "--kl needs --mode lmm" --kl 3
refused "--lmm-volume needs --mode lmm" --lmm-volume exact
refused "--area-samples needs --area-radius" --mode whitted --area-samples 4
refused "--scheme refract-both needs --mode lmm" --scheme refract-both
refused "--spp: expected an integer from 1 to 16777216, found '-1'" --spp -1
refused "--mode: unknown value 'foo'; expected one of: reference, whitted, lmm" --mode foo
[ -e "$dir/x.exr" ] && { echo "FAIL: an image was written after a refusal"; fail=1; }
# The stats of a reference hold no method's keys; lmm's hold the caustic
# pass's time inside the whole call's.
grep -q '"mesh_step"\|"caustic' "$dir/a.json" && { echo "FAIL: lmm keys in a reference's stats"; fail=1; }
# ...and its noise estimate, a number.
near "noise estimate" "$(field "$dir/a.json" noise_rel_rms_estimate)" 0.5 0.5
# A reference noisier than the 1% it is judged at says so.
"$tool" "$dir/good.json" -o "$dir/n.exr" --spp 1 --width 64 2>"$dir/err"; check "noisy reference" 0 $?
message_has "noisy reference" "$dir/err" "this reference's own noise is about"
# render.scheme is the light meshes' option, checked by the renderer at its
# place.
basic_scene "$dir/scheme.json" 16 12 "$POINT_LIGHT" "" ', "render": {"scheme": "both"}'
"$tool" "$dir/scheme.json" -o "$dir/x.exr" -q 2>"$dir/err"; check "render.scheme both" 2 $?
grep -q "scheme.json:9:[0-9]*: render.scheme: unknown value 'both'; expected one of: straight, refract-trace, refract-both" "$dir/err" \
  || { echo "FAIL: render.scheme message: $(cat "$dir/err")"; fail=1; }
# Without a medium there are no medium samples and no noise to estimate;
# the caustic pass's keys belong to refract-both.
grep -v '"medium"\|"bounds"' "$dir/good.json" >"$dir/dry.json"
"$tool" "$dir/dry.json" -o "$dir/dry.exr" --mode lmm --stats "$dir/dry.json.stats" -q; check "no medium" 0 $?
for key in medium_samples noise_rel_rms_estimate volume_lookups caustic_seconds; do
  grep -q "\"$key\"" "$dir/dry.json.stats" && { echo "FAIL: stats key $key does not apply"; fail=1; }
done
grep -q '"mesh_step"' "$dir/dry.json.stats" || { echo "FAIL: lmm stats without a medium"; fail=1; }
# A crop is the same pixels as the whole image's, to the bit.
"$tool" "$dir/good.json" -o "$dir/crop.exr" --spp 4 --crop 3 2 13 9 -q; check "--crop render" 0 $?
oiiotool "$dir/a.exr" --cut 10x7+3+2 -o "$dir/cut.exr"
idiff -fail 0 -failpercent 0 "$dir/cut.exr" "$dir/crop.exr" >/dev/null \
  || { echo "FAIL: the crop differs from the whole image's region"; fail=1; }
# Pixels, not bytes: the EXR header carries the time of writing.
idiff -fail 0 -failpercent 0 "$dir/a.exr" "$dir/b.exr" >/dev/null \
  || { echo "FAIL: same command, different image"; fail=1; }
# A scene path of more than 5000 characters (25 nested directories of 199,
# made one at a time: the whole path is longer than open(2) takes) is
# named whole in the error, not cut (issue 11, kind 5).
part=$(printf 'd%.0s' $(seq 199))
long="$dir"
(cd "$dir" && for i in $(seq 25); do mkdir "$part" && cd "$part" || exit 1; done && cp "$dir/good.json" scene.json) \
  || { echo "FAIL: could not make the nested directories"; fail=1; }
for i in $(seq 25); do long="$long/$part"; done
long="$long/scene.json"
"$tool" "$long" -o "$dir/long.exr" -q 2>"$dir/err"; check "a scene path of ${#long} characters" 2 $?
message_has "the long path whole" "$dir/err" "lmm_tracer: error: $long: cannot open the scene file: File name too long"
exit $fail
