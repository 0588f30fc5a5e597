#!/usr/bin/env bash
# shafts_compare on images with known errors: an image against itself, the
# same image 10% brighter, one with negative values, one of another size, and
# bad arguments. The test images come from lmm_tracer and oiiotool.
set -u
tool=$1 tracer=$2
. "$(dirname "$0")/../tools/cli_test_lib.sh"

basic_scene "$dir/s.json" 24 16 "$POINT_LIGHT"
sed 's/"width": 24/"width": 12/' "$dir/s.json" >"$dir/small.json"
"$tracer" "$dir/s.json" -o "$dir/ref.exr" --spp 8 -q || { echo "FAIL: render"; exit 1; }
"$tracer" "$dir/small.json" -o "$dir/small.exr" --spp 8 -q || { echo "FAIL: render"; exit 1; }
oiiotool "$dir/ref.exr" --mulc 1.1 -d float -o "$dir/bright.exr"
oiiotool "$dir/ref.exr" --subc 1 -d float -o "$dir/negative.exr"

"$tool" --help >"$dir/help"; check "--help" 0 $?
grep -q "usage: shafts_compare" "$dir/help" || { echo "FAIL: help text"; fail=1; }

"$tool" "$dir/ref.exr" "$dir/ref.exr" --json >"$dir/same.json"; check "same" 0 $?
near "same rel_rms" "$(field "$dir/same.json" rel_rms)" 0 0
[ "$(field "$dir/same.json" psnr)" = "None" ] || { echo "FAIL: psnr of identical images is not null"; fail=1; }

"$tool" "$dir/ref.exr" "$dir/bright.exr" --json --diff "$dir/d.png" \
  --preview "$dir/p.png" >"$dir/bright.json"; check "bright" 0 $?
near "bright rel_rms" "$(field "$dir/bright.json" rel_rms)" 0.1 1e-5
near "bright mean_rel" "$(field "$dir/bright.json" mean_rel)" 0.1 1e-5
near "bright scale" "$(field "$dir/bright.json" scale)" 1.1 1e-5
near "bright bad_values" "$(field "$dir/bright.json" bad_values)" 0 0
for f in d.png p.png; do [ -s "$dir/$f" ] || { echo "FAIL: $f not written"; fail=1; }; done
"$tool" "$dir/ref.exr" "$dir/bright.exr" --diff "$dir/d.exr" >/dev/null; check "exr diff" 0 $?
# An output that is an input or the other output is refused, nothing written.
cp "$dir/bright.exr" "$dir/keep.exr"
"$tool" "$dir/ref.exr" "$dir/bright.exr" --diff "$dir/./bright.exr" >/dev/null 2>"$dir/err"
check "--diff is the image" 2 $?
message_has "--diff is the image" "$dir/err" "must not overwrite an input"
cmp -s "$dir/bright.exr" "$dir/keep.exr" || { echo "FAIL: --diff overwrote the image"; fail=1; }
"$tool" "$dir/ref.exr" "$dir/bright.exr" --diff "$dir/q.png" --preview "$dir/q.png" >/dev/null 2>&1
check "--diff is --preview" 2 $?
# A refused or failed run with -p leaves no directory it made and keeps
# those that were there (issue 11): a --preview name too long is refused
# before --diff's directory is made; an image that does not load removes
# the directories made.
mkdir -p "$dir/pp/keep"
"$tool" "$dir/ref.exr" "$dir/bright.exr" --diff "$dir/pp/keep/a/d.png" \
  --preview "$dir/pp/keep/b/$(printf 'z%.0s' $(seq 300)).png" -p >/dev/null 2>"$dir/err"
check "-p, a name too long" 2 $?
message_has "-p, a name too long" "$dir/err" "File name too long"
"$tool" "$dir/ref.exr" "$dir/missing.exr" --diff "$dir/pp/keep/a/b/d.png" -p >/dev/null 2>&1
check "-p, an image that does not load" 2 $?
[ "$(cd "$dir/pp" && find . | sort | tr '\n' ' ')" = ". ./keep " ] \
  || { echo "FAIL: -p runs refused left: $(cd "$dir/pp" && find .)"; fail=1; }
rm -rf "$dir/pp"
[ -e "$dir/q.png" ] && { echo "FAIL: a refused compare wrote q.png"; fail=1; }
[ -s "$dir/d.exr" ] || { echo "FAIL: d.exr not written"; fail=1; }
"$tool" "$dir/ref.exr" "$dir/bright.exr" --max-rel-rms 0.2 >/dev/null; check "within bound" 0 $?
"$tool" "$dir/ref.exr" "$dir/bright.exr" --max-rel-rms 0.05 >/dev/null 2>&1; check "over bound" 3 $?

grep -q "rel_rms  *relative RMS error over the lit region" "$dir/help" \
  || { echo "FAIL: --help does not define rel_rms"; fail=1; }

# An 8-bit sRGB preview against the linear reference: compared, with a warning;
# two EXR files: no warning.
"$tool" "$dir/ref.exr" "$dir/ref.exr" --preview "$dir/ref.png" >/dev/null 2>"$dir/err"
check "exr against exr" 0 $?
[ -s "$dir/err" ] && { echo "FAIL: a warning for two EXR files: $(cat "$dir/err")"; fail=1; }
"$tool" "$dir/ref.exr" "$dir/ref.png" >/dev/null 2>"$dir/err"; check "exr against png" 0 $?
grep -q "warning: .*ref.exr is linear float radiance and .*ref.png a display-encoded" "$dir/err" \
  || { echo "FAIL: no warning for an sRGB image against a linear one"; fail=1; }

"$tool" "$dir/ref.exr" "$dir/negative.exr" --json >"$dir/neg.json"; check "negative" 0 $?
python3 -c 'import json,sys; sys.exit(json.load(open(sys.argv[1]))["bad_values"] == 0)' "$dir/neg.json" \
  || { echo "FAIL: negative values not counted"; fail=1; }
"$tool" "$dir/ref.exr" "$dir/negative.exr" --max-rel-rms 100 >/dev/null 2>&1; check "bad values fail the bound" 3 $?

"$tool" "$dir/ref.exr" "$dir/small.exr" >/dev/null 2>"$dir/err"; check "size mismatch" 2 $?
message_has "size mismatch" "$dir/err" "'$dir/small.exr' is 12x16 and the reference '$dir/ref.exr' 24x16: the images must be the same size"
"$tool" "$dir/ref.exr" "$dir/missing.exr" >/dev/null 2>&1; check "missing image" 2 $?
"$tool" "$dir/ref.exr" >/dev/null 2>&1; check "one image" 2 $?
"$tool" "$dir/ref.exr" "$dir/ref.exr" --lit 2 >/dev/null 2>"$dir/err"; check "bad --lit" 2 $?
message_has "bad --lit" "$dir/err" "shafts_compare: error: --lit: expected a number in [0, 1"
# The help's exit status line names this tool's bad input: images, no scene.
"$tool" --help | tr '\n' ' ' | tr -s ' ' >"$dir/help"
message_has "--help" "$dir/help" "2 for bad input (arguments, a missing or unreadable image)"
"$tool" "$dir/ref.exr" "$dir/ref.exr" --diff "$dir/x.tga" >/dev/null 2>&1; check "bad diff name" 2 $?
"$tool" "$dir/ref.exr" "$dir/ref.exr" --bogus >/dev/null 2>&1; check "unknown option" 2 $?
[ -e "$dir/x.tga" ] && { echo "FAIL: an output was written after an error"; fail=1; }

[ $fail = 0 ] && echo "shafts_compare: all checks passed"
exit $fail
