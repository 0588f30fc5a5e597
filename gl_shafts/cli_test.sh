#!/usr/bin/env bash
# Command-line behaviour of gl_shafts: help, bad arguments and bad scenes
# exit with status 2 and write nothing, a good render writes every output
# and a statistics file with the time split and the counts, scene render
# keys are defaults that options override; --backend picks the GL context's
# backend and --stats reports it, and a backend that cannot give a context is
# a clear error (CTest runs this once per backend, SHAFTS_GL_BACKEND set).
set -u
tool=$1
. "$(dirname "$0")/../tools/cli_test_lib.sh"

"$tool" --help >"$dir/help" 2>&1; check "--help" 0 $?
grep -q "usage: gl_shafts" "$dir/help" || { echo "FAIL: --help text"; fail=1; }
for opt in --planes --lattice --light-map-res --shadow-map-res --xi --jitter \
           --no-jitter --exposure --stats --quiet --backend; do
  grep -q -- "$opt" "$dir/help" || { echo "FAIL: --help does not mention $opt"; fail=1; }
done

basic_scene "$dir/good.json" 32 24 \
  '{"type": "spot", "position": [0, 2.5, 0], "look_at": [0, 0, 0], "intensity": [5, 5, 5], "outer_angle_deg": 30}' \
  ', {"type": "sphere", "material": "floor", "center": [0, 1, 0], "radius": 0.3}' \
  ', "render": {"planes": 7, "lattice": [3, 4], "xi": "exact", "jitter": true}'

run_bad() { # description, arguments...
  local d=$1; shift
  "$tool" "$@" >"$dir/out" 2>&1; check "$d" 2 $?
  grep -q "gl_shafts" "$dir/out" || { echo "FAIL: $d: no message"; fail=1; }
}
run_bad "no arguments"
run_bad "missing -o" "$dir/good.json"
run_bad "bad extension" "$dir/good.json" -o "$dir/x.tga"
run_bad "--planes 0" "$dir/good.json" -o "$dir/x.exr" --planes 0
run_bad "--planes junk" "$dir/good.json" -o "$dir/x.exr" --planes 12x
run_bad "--lattice 1 5" "$dir/good.json" -o "$dir/x.exr" --lattice 1 5
run_bad "--lattice one value" "$dir/good.json" -o "$dir/x.exr" --lattice 5
run_bad "--xi bogus" "$dir/good.json" -o "$dir/x.exr" --xi bogus
run_bad "--shadow-map-res 0" "$dir/good.json" -o "$dir/x.exr" --shadow-map-res 0
run_bad "--light-map-res 99999" "$dir/good.json" -o "$dir/x.exr" --light-map-res 99999
run_bad "--exposure nan" "$dir/good.json" -o "$dir/x.exr" --exposure nan
run_bad "--backend vulkan" "$dir/good.json" -o "$dir/x.exr" --backend vulkan
run_bad "unknown option" "$dir/good.json" -o "$dir/x.exr" --bogus
run_bad "two scenes" "$dir/good.json" "$dir/good.json" -o "$dir/x.exr"
bad_scenes_refused "$tool" "$dir/good.json"
camera_at_light_warns "$tool"
# Height fog is rendered (issue 12 part 3).
height_fog_scene "$dir/good.json" "$dir/fog.json"
"$tool" "$dir/fog.json" -o "$dir/fog_out.exr" -q; check "height fog renders" 0 $?
[ -s "$dir/fog_out.exr" ] || { echo "FAIL: height fog: no output"; fail=1; }
rm -f "$dir/fog.json" "$dir/fog_out.exr"
# So is the cornette_shanks phase function in the sweep's media.
sed 's/"medium": {"sigma_s"/"medium": {"phase": {"type": "cornette_shanks", "g": 0.7}, "sigma_s"/' \
  "$dir/good.json" >"$dir/cs.json"
"$tool" "$dir/cs.json" -o "$dir/cs_out.exr" -q; check "cornette_shanks renders" 0 $?
[ -s "$dir/cs_out.exr" ] || { echo "FAIL: cornette_shanks: no output"; fail=1; }
rm -f "$dir/cs.json" "$dir/cs_out.exr"
# A finite double that is no float (a camera 1e39 away) never becomes a
# shader literal or a uniform: a clear error, not a shader that fails to
# compile.
sed 's/"position": \[0, 1, 5\]/"position": [0, 1, 1e39]/' "$dir/good.json" >"$dir/far.json"
"$tool" "$dir/far.json" -o "$dir/x.exr" -q 2>"$dir/err"; check "camera at 1e39" 2 $?
grep -q "not a finite single-precision number" "$dir/err" && ! grep -q "compile" "$dir/err" \
  || { echo "FAIL: non-finite parameter message: $(cat "$dir/err")"; fail=1; }

"$tool" "$dir/good.json" -o "$dir/a.exr" -o "$dir/a.png" --stats "$dir/a.json" -q
check "good render" 0 $?
for f in a.exr a.png a.json; do
  [ -s "$dir/$f" ] || { echo "FAIL: $f not written"; fail=1; }
done
for key in seconds shadow_seconds surface_seconds plane_seconds \
           readback_seconds setup_seconds planes fragments fragments_rasterized \
           shadow_maps lights_swept renderer backend vendor \
           programs_compiled programs_cached sub_angle_deg; do
  grep -q "\"$key\"" "$dir/a.json" || { echo "FAIL: stats key $key"; fail=1; }
done
# Nothing that does not apply: no lattice with xi exact, no light maps'
# settings without a light map, no directional light's.
for key in lattice_u lattice_v lattice_seconds lattice_points light_map_res \
           sub_texels planes_directional shadow_map_res_directional; do
  grep -q "\"$key\"" "$dir/a.json" && { echo "FAIL: stats key $key does not apply"; fail=1; }
done
# The scene's render keys are the defaults...
grep -q '"planes_per_light": 7' "$dir/a.json" || { echo "FAIL: render.planes not used"; fail=1; }
"$tool" "$dir/good.json" -o "$dir/c.exr" --stats "$dir/c.json" -q --xi lattice
for key in '"lattice_v": 4' '"lattice_seconds"' '"lattice_points"'; do
  grep -q "$key" "$dir/c.json" || { echo "FAIL: xi lattice: $key"; fail=1; }
done
grep -q '"xi": "exact"' "$dir/a.json" || { echo "FAIL: render.xi not used"; fail=1; }
grep -q '"jitter": 1' "$dir/a.json" || { echo "FAIL: render.jitter not used"; fail=1; }
# ...that options override.
"$tool" "$dir/good.json" -o "$dir/b.exr" --stats "$dir/b.json" -q --planes 9 \
  --lattice 5 6 --xi lattice --no-jitter --shadow-map-res 64 --light-map-res 8
check "options" 0 $?
for kv in '"planes_per_light": 9' '"lattice_u": 5' '"lattice_v": 6' '"xi": "lattice"' \
          '"jitter": 0' '"shadow_map_res": 64'; do
  grep -q "$kv" "$dir/b.json" || { echo "FAIL: option not applied: $kv"; fail=1; }
done
# --backend NAME is the backend used; without it (auto), the backend the
# environment narrows auto to.
backend=${SHAFTS_GL_BACKEND:-}
if [ -n "$backend" ]; then
  [ "$(field "$dir/a.json" backend)" = "$backend" ] \
    || { echo "FAIL: SHAFTS_GL_BACKEND=$backend, stats say $(field "$dir/a.json" backend)"; fail=1; }
  SHAFTS_GL_BACKEND= "$tool" "$dir/good.json" -o "$dir/d.exr" --backend "$backend" \
    --stats "$dir/d.json" -q
  check "--backend $backend" 0 $?
  [ "$(field "$dir/d.json" backend)" = "$backend" ] || { echo "FAIL: --backend $backend not used"; fail=1; }
fi
# With libglvnd shown no EGL driver, --backend egl fails with a message that
# names the key and what EGL lacked, and writes nothing.
if [ "$backend" = egl ]; then
  __EGL_VENDOR_LIBRARY_FILENAMES=/dev/null "$tool" "$dir/good.json" -o "$dir/y.exr" \
    --backend egl -q 2>"$dir/err"
  check "--backend egl without an EGL driver" 1 $?
  grep -q "gl_shafts: .*backend: the egl backend cannot give an OpenGL 4.5 core context: .*device platform" \
    "$dir/err" || { echo "FAIL: no-EGL message: $(cat "$dir/err")"; fail=1; }
  [ -e "$dir/y.exr" ] && { echo "FAIL: an output was written after the backend failed"; fail=1; }
fi
render_cli_common "$tool" "$dir/good.json"
render_files_distinct "$tool" "$dir/good.json"
# More lights than gl_shafts renders (GS_MAX_LIGHTS): refused at once with
# the count and the limit, exit 2; 256 are still accepted by the check.
python3 - "$dir/good.json" "$dir/many.json" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
s["lights"] = [dict(s["lights"][0], intensity=[0.01] * 3) for _ in range(257)]
json.dump(s, open(sys.argv[2], "w"))
PY
timeout 60 "$tool" "$dir/many.json" -o "$dir/m.exr" -q 2>"$dir/err"; check "257 lights" 2 $?
message_has "257 lights" "$dir/err" "many.json: lights: 257 lights: gl_shafts renders at most 256"
[ -e "$dir/m.exr" ] && { echo "FAIL: 257 lights wrote an image"; fail=1; }
# --stats holds numbers: planes and shadow maps by the kinds of light
# present, when no one number is given.
sed 's/"render": {"planes": 7, /"render": {/' "$dir/good.json" >"$dir/kinds.json"
"$tool" "$dir/kinds.json" -o "$dir/k.exr" --stats "$dir/k.json" -q; check "kinds" 0 $?
for kv in '"planes_local": 1' '"shadow_map_res_local": 1024'; do
  grep -q "$kv" "$dir/k.json" || { echo "FAIL: stats lack $kv: $(cat "$dir/k.json")"; fail=1; }
done
grep -q '"planes_directional"\|"planes_per_light"\|by light kind' "$dir/k.json" \
  && { echo "FAIL: stats of lights not in the scene, or text for a number"; fail=1; }
# render.lattice has gl_shafts' one limit, reported at its place.
sed 's/"lattice": \[3, 4\]/"lattice": [5000, 5000]/' "$dir/good.json" >"$dir/lattice.json"
"$tool" "$dir/lattice.json" -o "$dir/x.exr" -q 2>"$dir/err"; check "render.lattice 5000" 2 $?
grep -q "lattice.json:9:[0-9]*: render.lattice: expected an integer from 2 to 4096" "$dir/err" \
  || { echo "FAIL: render.lattice message: $(cat "$dir/err")"; fail=1; }
run_bad "--lattice 5000 5000 (the renderer's limit)" "$dir/good.json" -o "$dir/x.exr" --lattice 5000 5000
# The same command gives the same image (pixels, not bytes: EXR headers
# carry the time).
"$tool" "$dir/good.json" -o "$dir/c.exr" -q
idiff -fail 0 -failpercent 0 "$dir/a.exr" "$dir/c.exr" >/dev/null \
  || { echo "FAIL: same command, different image"; fail=1; }
exit $fail
