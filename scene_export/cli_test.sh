#!/usr/bin/env bash
# Command-line behaviour of scene_export: help; bad arguments, bad scenes and
# refused --strict exports exit with status 2 and write nothing; good exports
# write every file, the Blender script is the same bytes for every scene; and
# a scene whose names and file paths hold quotes, backslashes, newlines and
# Python code exports to a .pov that POV-Ray renders and to a Blender export
# that renders without running any of it.
#
#   cli_test.sh SCENE_EXPORT SOURCE_DIR
set -u
tool=$1
src=$2
data=$src/scene_export/testdata
. "$(dirname "$0")/../tools/cli_test_lib.sh"

"$tool" --help >"$dir/help" 2>&1; check "--help" 0 $?
grep -q "usage: scene_export" "$dir/help" || { echo "FAIL: --help text"; fail=1; }
rm "$dir/help"

out=$dir/out
mkdir "$out"
"$tool" >/dev/null 2>&1; check "no arguments" 2 $?
"$tool" "$data/point_medium.json" -o "$out/a.pov" 2>/dev/null; check "missing --to" 2 $?
"$tool" "$data/point_medium.json" --to pov 2>/dev/null; check "missing -o" 2 $?
"$tool" "$data/point_medium.json" --to maya -o "$out/a.pov" 2>"$dir/err"; check "bad --to" 2 $?
message_has "bad --to" "$dir/err" "scene_export: error: --to: unknown value 'maya'; expected one of: pov, blender, json"
"$tool" "$data/point_medium.json" --to pov 2>"$dir/err"
message_has "missing -o" "$dir/err" "scene_export: error: -o OUT is required"
"$tool" "$data/point_medium.json" --to pov -o "$out/a.pov" --quality best 2>/dev/null
check "bad --quality" 2 $?
"$tool" "$data/point_medium.json" --to pov -o "$out/a.pov" --bogus 2>/dev/null
check "unknown option" 2 $?
"$tool" "$data/point_medium.json" --to pov -o "$out/a.txt" 2>/dev/null; check "not .pov" 2 $?
"$tool" "$data/point_medium.json" --to blender -o "$out/a.txt" 2>/dev/null; check "not .py" 2 $?
"$tool" "$data/point_medium.json" --to pov -o "$out/a b.pov" 2>"$dir/err"
check "unquotable POV-Ray name" 2 $?
grep -q "must consist of letters" "$dir/err" || { echo "FAIL: name message: $(cat "$dir/err")"; fail=1; }
"$tool" "$dir/missing.json" --to pov -o "$out/a.pov" 2>/dev/null; check "missing scene" 2 $?
# Height fog (issue 12): POV-Ray and Blender write it exactly (--strict
# passes: a density function, a node graph); the cornette_shanks phase is
# approximated by both (a note; --strict refuses and writes nothing).
height_fog_scene "$data/point_medium.json" "$dir/fog.json"
sed 's/"medium": {"sigma_s"/"medium": {"phase": {"type": "cornette_shanks", "g": 0.7}, "sigma_s"/' \
  "$data/point_medium.json" >"$dir/cs.json"
for to in pov:pov blender:py; do
  "$tool" "$dir/fog.json" --to "${to%%:*}" --strict -o "$dir/fog_out.${to##*:}" 2>"$dir/err"
  check "--to ${to%%:*} --strict writes height fog" 0 $?
  "$tool" "$dir/cs.json" --to "${to%%:*}" --strict -o "$dir/cs_out.${to##*:}" 2>"$dir/err"
  check "--to ${to%%:*} --strict refuses cornette_shanks" 2 $?
  # POV-Ray sums its frames, so it takes the signed three-lobe fit; Cycles
  # one non-negative lobe.
  case "$to" in
  pov*) note="no cornette_shanks phase; it is rendered as 3 Henyey-Greenstein lobes fitted to it, g = 0.7029 (weight 1.217), 0.2624 (weight -0.331)" ;;
  *) note="no cornette_shanks phase; it is rendered as one Henyey-Greenstein lobe fitted to it, g = 0.7433" ;;
  esac
  grep -qF "$note" "$dir/err" || { echo "FAIL: cornette_shanks note: $(cat "$dir/err")"; fail=1; }
  ls "$dir" | grep -q '^cs_out' && { echo "FAIL: a refused export wrote an output"; fail=1; }
done
grep -q 'function { min(1, exp((' "$dir/fog_out.pov" \
  || { echo "FAIL: the POV-Ray export has no density function"; fail=1; }
grep -q '"height_fog": {' "$dir/fog_out.blender.json" \
  || { echo "FAIL: the Blender export has no height fog"; fail=1; }
# Cornette-Shanks g 0.5: POV-Ray renders its three signed lobes (weights
# 1.52, -0.95, 0.43) in three frames, the later ones with their lobe's
# scattering only, the negative one subtracted by the summing step.
sed 's/"g": 0.7/"g": 0.5/' "$dir/cs.json" >"$dir/cs5.json"
"$tool" "$dir/cs5.json" --to pov -o "$dir/cs5_out.pov" --width 16 2>"$dir/err"
check "--to pov writes three signed Cornette-Shanks lobes" 0 $?
grep -qF "rendered as 3 Henyey-Greenstein lobes fitted to it, g = 0.5048 (weight 1.521), 0.1834 (weight -0.9524) and -0.06121 (weight 0.4315), one frame each, a negative weight's frame subtracted" "$dir/err" \
  || { echo "FAIL: three-lobe note: $(cat "$dir/err")"; fail=1; }
grep -q '^Final_Frame=3$' "$dir/cs5_out.ini" && grep -q '^; Frame_Signs=+ - +$' "$dir/cs5_out.ini" \
  && grep -q '#if (frame_number = 2) // lobe 2: g 0.1834, weight -0.9524' "$dir/cs5_out.pov" \
  && grep -qF 'cs5_out2.exr --sub cs5_out3.exr --add -o cs5_out.exr' "$dir/cs5_out.pov" \
  || { echo "FAIL: the signed lobes' frames are missing"; fail=1; }
# It says what it wrote and the commands that make the image (README.md);
# they do, here at 16x12: POV-Ray's frames, then their signed sum.
message_has "wrote line" "$dir/err" "scene_export: wrote $dir/cs5_out.pov, $dir/cs5_out.ini"
render="cd $dir && povray cs5_out.ini && oiiotool cs5_out1.exr cs5_out2.exr --sub cs5_out3.exr --add -o cs5_out.exr"
message_has "render line" "$dir/err" "scene_export: render: $render"
# The .pov's header lists the approximations as written (printable ASCII
# kept in a comment).
message_has "the header's approximations" "$dir/cs5_out.pov" "// - medium: POV-Ray has no cornette_shanks phase; it is rendered as 3 Henyey-Greenstein lobes fitted to it, g = 0.5048 (weight 1.521)"
message_has "the .ini's note" "$dir/cs5_out.ini" "; POV-Ray writes the frames cs5_out1.exr to cs5_out3.exr, not cs5_out.exr: cs5_out.exr is"
if command -v povray >/dev/null && command -v oiiotool >/dev/null; then
  (eval "$(sed -n 's/^scene_export: render: //p' "$dir/err")") >"$dir/render.log" 2>&1
  check "the printed render commands" 0 $?
  iinfo "$dir/cs5_out.exr" 2>/dev/null | grep -Eq "16 x +12," \
    || { echo "FAIL: the render commands made no image: $(tail -5 "$dir/render.log")"; fail=1; }
fi
# One frame: POV-Ray alone; Blender: its command line; -q: nothing.
"$tool" "$data/point_medium.json" --to pov -o "$dir/one_out.pov" 2>"$dir/err"
message_has "one-frame render line" "$dir/err" "scene_export: render: cd $dir && povray one_out.ini"
grep -q "oiiotool\|not one_out.exr" "$dir/err" "$dir/one_out.ini" && { echo "FAIL: a one-frame export sums frames"; fail=1; }
"$tool" "$data/point_medium.json" --to blender -o "$dir/one_out.py" 2>"$dir/err"
message_has "blender render line" "$dir/err" "scene_export: render: blender -b -P $dir/one_out.py -- --engine cycles --out $dir/one_out.exr"
"$tool" "$dir/cs5.json" --to pov -o "$dir/one_out.pov" -q 2>"$dir/err"; check "-q" 0 $?
[ -s "$dir/err" ] && { echo "FAIL: -q printed: $(cat "$dir/err")"; fail=1; }
rm -f "$dir"/one_out*
rm -f "$dir"/fog_out.* "$dir"/cs5_out.* "$dir/cs.json" "$dir/cs5.json"
# The atmosphere: POV-Ray and Blender write it (approximated: --strict
# refuses), and the Blender script refuses it for EEVEE with its reason.
"$tool" "$src/scenes/sky_sunset.json" --to pov -o "$dir/sky_out.pov" 2>"$dir/err"
check "--to pov writes the atmosphere" 0 $?
grep -q "cornette_shanks phase" "$dir/err" || { echo "FAIL: atmosphere note: $(cat "$dir/err")"; fail=1; }
"$tool" "$src/scenes/sky_sunset.json" --to pov --strict -o "$dir/sky2_out.pov" 2>/dev/null
check "--to pov --strict refuses the atmosphere's Mie phase" 2 $?
"$tool" "$src/scenes/sky_sunset.json" --to blender -o "$dir/sky_out.py" 2>"$dir/err"
check "--to blender writes the atmosphere" 0 $?
grep -q "cornette_shanks phase" "$dir/err" || { echo "FAIL: atmosphere note: $(cat "$dir/err")"; fail=1; }
"$tool" "$src/scenes/sky_sunset.json" --to blender --strict -o "$dir/sky2_out.py" 2>/dev/null
check "--to blender --strict refuses the atmosphere's phases" 2 $?
blender -b --factory-startup -P "$dir/sky_out.py" -- --engine eevee --out "$dir/sky_eevee.exr" \
  >"$dir/err" 2>&1
check "the script refuses the atmosphere for EEVEE" 2 $?
grep -q "medium.atmosphere: EEVEE does not render" "$dir/err" \
  || { echo "FAIL: EEVEE refusal: $(tail -3 "$dir/err")"; fail=1; }
ls "$dir" | grep -qE '^(sky2_out|sky_eevee)' \
  && { echo "FAIL: a refused export or render wrote an output"; fail=1; }
rm -f "$dir"/sky_out.* "$dir"/sky_out[0-9]*
height_fog_scene "$data/point_medium.json" "$dir/fog.json"
"$tool" "$dir/fog.json" --to json -o "$dir/fog2.json"; check "json keeps height fog" 0 $?
grep -q '"height_fog"' "$dir/fog2.json" && grep -q '"scale_height": 1' "$dir/fog2.json" \
  || { echo "FAIL: json export lost the height fog"; fail=1; }
rm -f "$dir/fog.json" "$dir/fog2.json"
sed 's/"intensity"/"intensty"/' "$data/point_medium.json" >"$dir/typo.json"
"$tool" "$dir/typo.json" --to pov -o "$out/a.pov" 2>"$dir/err"; check "misspelled key" 2 $?
grep -q "typo.json:.*lights\[0\].*did you mean 'intensity'" "$dir/err" \
  || { echo "FAIL: misspelled-key message: $(cat "$dir/err")"; fail=1; }
"$tool" "$data/point_medium.json" --to pov -o "$dir/nowhere/a.pov" 2>/dev/null
check "missing output directory" 2 $?
"$tool" "$data/point_medium.json" --to pov -o "$out/a.pov" --quality 2>"$dir/err"
check "value missing last" 2 $?
grep -q "quality needs a value" "$dir/err" || { echo "FAIL: value message: $(cat "$dir/err")"; fail=1; }
version_ok "$tool"
# --help lists every target of the table, with the file it writes.
"$tool" --help >"$dir/help"
for t in "--to pov" "--to blender" "--to json" "pov|blender|json"; do
  grep -qF -- "$t" "$dir/help" || { echo "FAIL: --help lacks '$t'"; fail=1; }
done
"$tool" "$data/point_medium.json" --to json -o "$dir/made/by/p.json" -p; check "-p" 0 $?
[ -s "$dir/made/by/p.json" ] || { echo "FAIL: -p did not write"; fail=1; }
rm -rf "$dir/made"
# A refused or failed run with -p leaves no directory it made and keeps
# those that were there (issue 11).
mkdir -p "$dir/pp/keep"
"$tool" "$data/point_medium.json" --to json -o "$dir/pp/keep/g/$(printf 'z%.0s' $(seq 300)).json" -p 2>"$dir/err"
check "-p, a name too long" 2 $?
message_has "-p, a name too long" "$dir/err" "File name too long"
"$tool" "$dir/missing.json" --to json -o "$dir/pp/keep/g/h/p.json" -p 2>/dev/null
check "-p, a scene that does not load" 2 $?
[ "$(cd "$dir/pp" && find . | sort | tr '\n' ' ')" = ". ./keep " ] \
  || { echo "FAIL: -p runs refused left: $(cd "$dir/pp" && find .)"; fail=1; }
rm -rf "$dir/pp"
empty "failed exports" "$out"
# No file of an export may be the scene, whatever its spelling: the JSON
# export over its own scene, the Blender export whose data file
# (NAME.blender.json) is the scene. Refused with 2, the scene unchanged.
cp "$data/point_medium.json" "$out/S.json"
"$tool" "$out/S.json" --to json -o "$out/./S.json" 2>"$dir/err"; check "json export over its scene" 2 $?
grep -q "is the same file as the scene.*must not overwrite an input" "$dir/err" \
  || { echo "FAIL: same-file message: $(cat "$dir/err")"; fail=1; }
cp "$out/S.json" "$out/T.blender.json"
"$tool" "$out/T.blender.json" --to blender -o "$out/T.py" 2>/dev/null; check "blender data file over its scene" 2 $?
cmp -s "$out/S.json" "$data/point_medium.json" && cmp -s "$out/T.blender.json" "$data/point_medium.json" \
  || { echo "FAIL: a refused export changed its scene"; fail=1; }
[ -e "$out/T.py" ] && { echo "FAIL: a refused export wrote T.py"; fail=1; }
rm "$out/S.json" "$out/T.blender.json"
empty "refused exports" "$out"
# Paths of any length: a POV-Ray export 1500 characters deep writes its
# light map beside the .pov under its own name (fixed 1200-byte buffers
# cut the name and wrote the map over another file).
long=$out
for i in 1 2 3 4 5 6; do long=$long/$(printf 'd%.0s' $(seq 250)); done
mkdir -p "$long"
"$tool" "$data/spot_gobo.json" --to pov -o "$long/g.pov" 2>/dev/null; check "a 1500-character path" 0 $?
[ -s "$long/g_map0.exr" ] && [ -s "$long/g.pov" ] && [ -s "$long/g.ini" ] \
  || { echo "FAIL: the long-path export: $(ls "$long")"; fail=1; }
[ "$(find "$out" -type f | wc -l)" = 3 ] || { echo "FAIL: long-path export files: $(find "$out" -type f)"; fail=1; }
# ...and so does the Blender export (se_blender.c's light map path had
# the same buffers).
"$tool" "$data/spot_gobo.json" --to blender -o "$long/g.py" 2>/dev/null; check "a 1500-character path, blender" 0 $?
[ -s "$long/g_blender_map0.exr" ] && [ -s "$long/g_blender_eevee_map0.exr" ] && [ -s "$long/g.py" ] && [ -s "$long/g.blender.json" ] \
  || { echo "FAIL: the long-path blender export: $(ls "$long")"; fail=1; }
[ "$(find "$out" -type f | wc -l)" = 7 ] || { echo "FAIL: long-path export files: $(find "$out" -type f)"; fail=1; }
rm -rf "$out"/d*
# The JSON export names files relative to itself: written elsewhere, it
# carries copies of the scene's files and loads from there; a scene file
# naming a file by an absolute path is refused (exit 2).
"$tool" "$data/spot_gobo.json" --to json -o "$out/n.json" 2>/dev/null; check "json export elsewhere" 0 $?
grep -q '"image": "n.map0.png"' "$out/n.json" || { echo "FAIL: the export's light map name: $(grep image "$out/n.json")"; fail=1; }
cmp -s "$out/n.map0.png" "$data/assets/$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["lights"][0]["light_map"]["image"].split("/")[-1])' "$data/spot_gobo.json")" \
  || { echo "FAIL: the copied light map differs"; fail=1; }
"$tool" "$out/n.json" --to json -o "$out/m.json" 2>/dev/null; check "the export loads again" 0 $?
grep -q '"image": "n.map0.png"' "$out/m.json" || { echo "FAIL: a file inside the tree is named, not copied"; fail=1; }
sed "s|\"n.map0.png\"|\"$out/n.map0.png\"|" "$out/n.json" >"$out/abs.json"
"$tool" "$out/abs.json" --to json -o "$out/x.json" 2>"$dir/err"; check "an absolute file name" 2 $?
grep -q "lights\[0\].light_map.image: the file name '.*' is absolute" "$dir/err" \
  || { echo "FAIL: absolute-name message: $(cat "$dir/err")"; fail=1; }
# A mesh that names other files (an OBJ's material library) is not
# copied: the copy would not find them; the export is refused (exit 2,
# nothing written) unless it is written where the mesh's tree is.
mkdir -p "$dir/named"
printf 'newmtl grey\nKd 0.5 0.5 0.5\n' >"$dir/named/m.mtl"
printf 'mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl grey\nf 1 2 3\n' >"$dir/named/m.obj"
python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); d["shapes"].append({"type":"mesh","material":"floor","file":"m.obj"}); json.dump(d,open(sys.argv[2],"w"))' \
  "$data/lambert_floor.json" "$dir/named/s.json"
"$tool" "$dir/named/s.json" --to json -o "$out/named.json" 2>"$dir/err"; check "json export of a mesh naming files, elsewhere" 2 $?
grep -q "names other files" "$dir/err" || { echo "FAIL: named-files message: $(cat "$dir/err")"; fail=1; }
[ ! -e "$out/named.json" ] || { echo "FAIL: a refused export wrote its scene"; fail=1; }
"$tool" "$dir/named/s.json" --to json -o "$dir/named/e.json" 2>/dev/null; check "json export of a mesh naming files, in its tree" 0 $?
grep -q '"file": "m.obj"' "$dir/named/e.json" || { echo "FAIL: the mesh is not referred to: $(grep file "$dir/named/e.json")"; fail=1; }
rm -f "$out"/*

# --strict refuses approximations and writes nothing; exact exports pass.
"$tool" "$data/phase_nishita_hazy.json" --to blender -o "$out/h.py" --strict 2>"$dir/err"
check "--strict, Cycles without Nishita phases" 2 $?
grep -q "strict.*Henyey-Greenstein" "$dir/err" || { echo "FAIL: --strict message: $(cat "$dir/err")"; fail=1; }
"$tool" "$data/everything.json" --to pov -o "$out/e.pov" --strict 2>/dev/null
check "--strict, POV-Ray with a coloured highlight" 2 $?
empty "refused exports" "$out"
"$tool" "$data/phase_nishita_hazy.json" --to pov -o "$out/h.pov" --strict; check "--strict, exact" 0 $?
"$tool" "$data/phase_nishita_hazy.json" --to blender -o "$out/h.py" 2>"$dir/err"
check "approximation without --strict" 0 $?
grep -q "warning:.*Henyey-Greenstein" "$dir/err" || { echo "FAIL: no warning"; fail=1; }
grep -q "Henyey-Greenstein" "$out/h.blender.json" || { echo "FAIL: no note in the data"; fail=1; }
# A scene beyond what Cycles' single precision holds in its own units and
# position (about 1e-6 to 1e5 units in radius; docs/scene_export.md,
# "Precision"): lambert_floor.json (exact for Blender) scaled by 1e-9 and by
# 1e7. The exporter scales it (se_scale.h): exact, --strict accepts it, and
# --verbose and the data state the scale. With --scale none (its own
# units) it is refused by --strict with nothing written, and exported with
# a warning and a note without it.
sc=$dir/scaled_out
mkdir -p "$sc"
for k in 1e-9 1e7; do
  python3 - "$data/lambert_floor.json" "$dir/scaled.json" "$k" <<'PY'
import json, sys
s, k = json.load(open(sys.argv[1])), float(sys.argv[3])
def walk(o, key=""):
    if isinstance(o, dict):
        return {a: walk(b, a) for a, b in o.items()}
    if isinstance(o, list):
        return [walk(b, key) for b in o]
    if isinstance(o, (int, float)) and key in ("position", "look_at", "corner", "u", "v", "center",
                                               "min", "max", "radius"):
        return o * k
    return o
json.dump(walk(s), open(sys.argv[2], "w"))
PY
  "$tool" "$dir/scaled.json" --to blender -o "$sc/s.py" --strict -v 2>"$dir/err"
  check "--strict, a scene scaled by $k, scaled back" 0 $?
  grep -q "frame: lengths multiplied by" "$dir/err" || { echo "FAIL: --verbose: $(cat "$dir/err")"; fail=1; }
  grep -q '"frame": {"scale": 1e' "$sc/s.blender.json" || { echo "FAIL: no frame in the data"; fail=1; }
  rm -f "$sc"/*
  "$tool" "$dir/scaled.json" --to blender -o "$sc/s.py" --strict --scale none 2>"$dir/err"
  check "--strict --scale none, a scene scaled by $k" 2 $?
  grep -q "strict: with --scale none the scene is .* units across.*single precision" "$dir/err" \
    || { echo "FAIL: --strict scale message: $(cat "$dir/err")"; fail=1; }
  empty "the refused scaled export" "$sc"
  "$tool" "$dir/scaled.json" --to blender -o "$sc/s.py" --scale none 2>"$dir/err"
  check "a scene scaled by $k with --scale none, without --strict" 0 $?
  grep -q "warning: with --scale none the scene is .* units across" "$dir/err" || { echo "FAIL: no scale warning"; fail=1; }
  grep -q "single precision" "$sc/s.blender.json" || { echo "FAIL: no scale note in the data"; fail=1; }
  rm -f "$sc"/*
done
# --scale: a number forces it (the .pov states it), bad values are refused.
"$tool" "$data/lambert_floor.json" --to pov -o "$sc/f.pov" --scale 1e3; check "--scale 1e3" 0 $?
grep -q "lengths multiplied by 1000$" "$sc/f.pov" || { echo "FAIL: --scale 1e3 not in the .pov"; fail=1; }
rm -f "$sc"/*
for v in 0 -1 abc inf 1e3x; do
  "$tool" "$data/lambert_floor.json" --to pov -o "$sc/f.pov" --scale "$v" 2>"$dir/err"
  check "--scale $v" 2 $?
  grep -q "scale: expected auto, none or a positive number" "$dir/err" || { echo "FAIL: --scale $v: $(cat "$dir/err")"; fail=1; }
done
empty "refused --scale" "$sc"
# --width/--height: the image size of every target, worded and bounded as
# the renderers' options; alone, the other side follows the aspect (4:3).
for v in 0 65537 abc -3 2.5; do
  "$tool" "$data/lambert_floor.json" --to pov -o "$sc/f.pov" --width "$v" 2>"$dir/err"
  check "--width $v" 2 $?
  message_has "--width $v" "$dir/err" "scene_export: error: --width: expected an integer from 1 to 65536, found '$v'"
done
"$tool" "$data/lambert_floor.json" --to pov -o "$sc/f.pov" --height 0 2>"$dir/err"
check "--height 0" 2 $?
message_has "--height 0" "$dir/err" "scene_export: error: --height: expected an integer from 1 to 65536, found '0'"
empty "refused --width/--height" "$sc"
"$tool" "$data/lambert_floor.json" --to pov -o "$sc/f.pov" --width 40; check "--to pov --width 40" 0 $?
grep -qx "Width=40" "$sc/f.ini" && grep -qx "Height=30" "$sc/f.ini" \
  || { echo "FAIL: --width 40 in the .ini: $(grep -i 'width\|height' "$sc/f.ini")"; fail=1; }
"$tool" "$data/lambert_floor.json" --to pov -o "$sc/g.pov" --width 30 --height 10; check "--to pov, 30x10" 0 $?
grep -q "right x \* 3$" "$sc/g.pov" || { echo "FAIL: the .pov's aspect for 30x10: $(grep right "$sc/g.pov")"; fail=1; }
"$tool" "$data/lambert_floor.json" --to blender -o "$sc/f.py" --height 12; check "--to blender --height 12" 0 $?
grep -q '"render": {"width": 16, "height": 12,' "$sc/f.blender.json" \
  || { echo "FAIL: --height 12 in the Blender data: $(grep -o '"render": {[^}]*' "$sc/f.blender.json")"; fail=1; }
"$tool" "$data/lambert_floor.json" --to json -o "$sc/f.json" --width 10 --height 20; check "--to json, 10x20" 0 $?
[ "$(python3 -c 'import json,sys; c=json.load(open(sys.argv[1]))["camera"]; print(c["width"], c["height"])' "$sc/f.json")" = "10 20" ] \
  || { echo "FAIL: --width 10 --height 20 in the json camera"; fail=1; }
# The Blender script takes the same options after --, worded alike.
if command -v blender >/dev/null; then
  blender -b --factory-startup -P "$sc/f.py" -- --engine cycles --out "$sc/f.exr" --width 0 \
    >"$dir/err" 2>&1
  check "the script's --width 0" 2 $?
  message_has "the script's --width 0" "$dir/err" "scene_export script: error: --width: expected an integer from 1 to 65536, found '0'"
  [ -e "$sc/f.exr" ] && { echo "FAIL: the script's refused --width wrote an image"; fail=1; }
  # --samples as the C tools word a bad value, within Cycles' own bounds.
  for v in 0 16777217 -1 2.5; do
    blender -b --factory-startup -P "$sc/f.py" -- --out "$sc/f.exr" --samples "$v" >"$dir/err" 2>&1
    check "the script's --samples $v" 2 $?
    message_has "the script's --samples $v" "$dir/err" "scene_export script: error: --samples: expected an integer from 1 to 16777216, found '$v'"
  done
  # --out: an OpenEXR name (the image is EXR whatever it is called), in a
  # directory that exists and takes a file, checked before the scene is
  # built (a script without its data says so about --out, not the data).
  blender -b --factory-startup -P "$sc/f.py" -- --out "$sc/f.png" >"$dir/err" 2>&1
  check "the script's --out f.png" 2 $?
  message_has "the script's --out f.png" "$dir/err" "scene_export script: error: --out '$sc/f.png' must end in .exr"
  cp "$sc/f.py" "$sc/lonely.py"
  blender -b --factory-startup -P "$sc/lonely.py" -- --out "$sc/nowhere/f.exr" >"$dir/err" 2>&1
  check "the script's --out in a missing directory" 2 $?
  message_has "the script's --out in a missing directory" "$dir/err" "scene_export script: error: --out: directory '$sc/nowhere' does not exist"
  blender -b --factory-startup -P "$sc/f.py" -- --out /proc/f.exr >"$dir/err" 2>&1
  check "the script's --out in /proc" 2 $?
  message_has "the script's --out in /proc" "$dir/err" "scene_export script: error: --out: '/proc' is not a directory this user can write to"
  grep -q "probe\|tmp" "$dir/err" && { echo "FAIL: a temporary name in: $(cat "$dir/err")"; fail=1; }
  ls -A "$sc" | grep -q '\.png$\|\.exr$\|probe\|tmp' && { echo "FAIL: refused renders left: $(ls -A "$sc")"; fail=1; }
  blender -b --factory-startup -P "$sc/f.py" -- --help >"$dir/err" 2>&1
  check "the script's --help" 0 $?
  for t in "--engine cycles|eevee" "(default: cycles)" "32-bit float OpenEXR" "exit status: 0 success" \
           "2 bad arguments or data" "1 to 16777216"; do
    message_has "the script's --help" "$dir/err" "$t"
  done
fi
rm -f "$sc"/*
# A spot narrower than Blender's 1-degree spot_size (issue 11, a laser): a
# note, and --strict refuses; POV-Ray's spotlight holds any cone.
sed 's/"outer_angle_deg": 30, "inner_angle_deg": 20/"outer_angle_deg": 0.3/' \
  "$data/spot_sphere.json" >"$dir/laser.json"
"$tool" "$dir/laser.json" --to blender -o "$out/l.py" --strict 2>"$dir/err"
check "--strict, a 0.3-degree spot in Blender" 2 $?
grep -q "strict.*at least 1 degree wide" "$dir/err" || { echo "FAIL: narrow-spot message: $(cat "$dir/err")"; fail=1; }
[ -z "$(ls "$out" | grep '^l[._]')" ] || { echo "FAIL: the refused narrow-spot export wrote $(ls "$out")"; fail=1; }
"$tool" "$dir/laser.json" --to blender -o "$out/l.py" 2>"$dir/err"; check "narrow spot, approximate" 0 $?
grep -q "warning:.*widened to 0.5" "$dir/err" || { echo "FAIL: no narrow-spot warning: $(cat "$dir/err")"; fail=1; }
rm -f "$out"/l.* "$out"/l_*

# Good exports write every file; the script is one fixed file.
"$tool" "$data/spot_gobo.json" --to pov -o "$out/g.pov"; check "pov export" 0 $?
"$tool" "$data/spot_gobo.json" --to blender -o "$out/g.py"; check "blender export" 0 $?
"$tool" "$data/spot_gobo.json" --to json -o "$out/g.json.json"; check "json export" 0 $?
for f in h.pov h.ini h.py h.blender.json g.pov g.ini g_map0.exr g.py g.blender.json g_blender_map0.exr g.json.json; do
  [ -s "$out/$f" ] || { echo "FAIL: $f not written"; fail=1; }
done
cmp -s "$out/h.py" "$out/g.py" || { echo "FAIL: the Blender script differs between scenes"; fail=1; }
cmp -s "$out/h.py" "$src/blender_addon/shafts_blender/convert/blender_build.py" \
  || { echo "FAIL: the Blender script is not blender_build.py"; fail=1; }
ls "$out" | grep -q tmp && { echo "FAIL: a temporary file was left"; fail=1; }
"$tool" "$out/g.json.json" --to pov -o "$out/g2.pov"; check "export of the normalised scene" 0 $?

# The hostile scene: every user string holds a quote, a backslash, a
# newline and Python code; the files live in such a directory too.
evil=$'we"ird\\dir\n__import__(\'os\').system(\'touch pwned\')'
mkdir -p "$dir/$evil"
cp "$src/scenes/assets/gobo_dots.png" "$dir/$evil/gobo \"q\" \\ __import__('os').png"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n' \
  >"$dir/$evil/m\"e\\sh.obj"
python3 - "$dir" "$evil" <<'PY'
import json, sys
d, evil = sys.argv[1], sys.argv[2]
name = "glass\"\\\n__import__('os').system('touch pwned')"
scene = {
  "format": "shafts-scene", "version": 1,
  "camera": {"position": [0, 1.5, 5], "look_at": [0, 1, 0], "fov_y_deg": 45,
             "width": 32, "height": 24},
  "medium": {"sigma_s": [0.1, 0.1, 0.1], "bounds": {"min": [-2, 0, -2], "max": [2, 3, 2]}},
  "lights": [{"type": "spot", "position": [0, 2.8, 0], "direction": [0, -1, 0],
              "intensity": [20, 20, 20], "outer_angle_deg": 25,
              "light_map": {"image": "gobo \"q\" \\ __import__('os').png"}}],
  "materials": {name: {"diffuse": [0.5, 0.5, 0.5], "transmit": [0.3, 0.3, 0.3]},
                "__import__('os').system('touch pwned')": {"diffuse": [0.6, 0.6, 0.6]}},
  "shapes": [{"type": "box", "material": "__import__('os').system('touch pwned')",
              "min": [-2, -0.1, -2], "max": [2, 0, 2]},
             {"type": "mesh", "material": name, "file": "m\"e\\sh.obj",
              "transform": {"translate": [0, 1, 0], "scale": 0.5}}]}
with open(d + "/" + evil + "/sc\"ene\\ '__import__'.json", "w") as f:
    json.dump(scene, f)
PY
scene="$dir/$evil/sc\"ene\\ '__import__'.json"
pov=$dir/pov
mkdir "$pov"
"$tool" "$scene" --to pov -o "$pov/evil.pov"; check "hostile scene to pov" 0 $?
if command -v povray >/dev/null; then
  # POV-Ray's +W/+H after the .ini override its size (docs/scene_export.md).
  (cd "$pov" && povray evil.ini +W16 +H12 >"$dir/povray.log" 2>&1); check "povray renders the hostile scene" 0 $?
  [ -s "$pov/evil.exr" ] || { echo "FAIL: POV-Ray wrote no image"; tail -20 "$dir/povray.log"; fail=1; }
  iinfo "$pov/evil.exr" | grep -Eq "16 x +12," || { echo "FAIL: povray +W16 +H12: $(iinfo "$pov/evil.exr")"; fail=1; }
else
  echo "FAIL: povray is not installed"; fail=1
fi
# User text appears only in comments, on their own lines, with no block
# comment opened or closed.
grep -v '^ *//' "$pov/evil.pov" | grep -q -i 'import\|touch\|pwned' \
  && { echo "FAIL: user text outside comments in the .pov"; fail=1; }
grep -q '/\*\|\*/' "$pov/evil.pov" && { echo "FAIL: a block comment in the .pov"; fail=1; }
grep -qF "// materials[0]: glass\"\\___import__('os').system('touch pwned')" "$pov/evil.pov" \
  || { echo "FAIL: the hostile name's comment: $(grep 'materials\[0\]' "$pov/evil.pov")"; fail=1; }

blend=$dir/"bl\"end \\ dir"
mkdir "$blend"
"$tool" "$scene" --to blender -o "$blend/ev\"il \\ '__import__'.py"; check "hostile scene to blender" 0 $?
cmp -s "$blend/ev\"il \\ '__import__'.py" "$src/blender_addon/shafts_blender/convert/blender_build.py" \
  || { echo "FAIL: the hostile export's script is not the fixed script"; fail=1; }
if command -v blender >/dev/null; then
  # --width alone: the height follows the data's 32x24.
  (cd "$dir" && blender -b -P "$blend/ev\"il \\ '__import__'.py" -- --engine cycles \
     --out "$blend/evil.exr" --samples 2 --width 20 >"$dir/blender.log" 2>&1)
  check "blender renders the hostile scene" 0 $?
  [ -s "$blend/evil.exr" ] || { echo "FAIL: Blender wrote no image"; tail -20 "$dir/blender.log"; fail=1; }
  iinfo "$blend/evil.exr" | grep -Eq "20 x +15," || { echo "FAIL: the script's --width 20: $(iinfo "$blend/evil.exr")"; fail=1; }
else
  echo "FAIL: blender is not installed"; fail=1
fi
found=$(find "$dir" . -name pwned 2>/dev/null)
[ -n "$found" ] && { echo "FAIL: the scene's text was executed: $found"; fail=1; }
"$tool" "$scene" --to json -o "$dir/evil.json"; check "hostile scene to json" 0 $?
"$tool" "$dir/evil.json" --to pov -o "$pov/again.pov"; check "hostile normalised scene reloads" 0 $?
exit $fail
