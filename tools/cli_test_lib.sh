# Sourced by the command-line tests (gl_shafts, lmm_tracer, scene_export,
# validation): a scratch directory $dir removed on exit, a failure flag $fail
# that the test returns, and checks that report a failure and go on.
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fail=0
check() { # description, expected status, actual status
  if [ "$2" != "$3" ]; then echo "FAIL: $1: exit $3, expected $2"; fail=1; fi
}
empty() { # description, directory: nothing may have been written there
  if [ -n "$(ls -A "$2")" ]; then echo "FAIL: $1 wrote: $(ls -A "$2")"; fail=1; fi
}
field() { # json file, key: prints the value
  python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))[sys.argv[2]])' "$1" "$2"
}
near() { # description, value, expected, tolerance
  if ! python3 -c 'import sys; a,b,t=map(float,sys.argv[1:]); sys.exit(abs(a-b)>t)' "$2" "$3" "$4"; then
    echo "FAIL: $1: $2, expected $3 +- $4"; fail=1
  fi
}
version_ok() { # tool: --version prints "NAME X.Y.Z" and exits 0
  local out
  out=$("$1" --version); check "--version" 0 $?
  echo "$out" | grep -Eq "^$(basename "$1") [0-9]+\.[0-9]+\.[0-9]+$" \
    || { echo "FAIL: --version printed '$out'"; fail=1; }
}
message_has() { # description, file, text
  grep -qF -- "$3" "$2" || { echo "FAIL: $1: no '$3' in: $(cat "$2")"; fail=1; }
}
# The behaviour both renderers share: --version, honest option errors, the
# output directory checked (and made with -p) before rendering, --width and
# --height, one "rendered in" line, provenance in the EXR header.
render_cli_common() { # tool, good scene (4:3), extra arguments...
  local tool=$1 scene=$2 name
  shift 2
  name=$(basename "$tool")
  version_ok "$tool"
  "$tool" "$scene" -o "$dir/x.exr" --bogus 2>"$dir/err"; check "unknown option last" 2 $?
  message_has "unknown option last" "$dir/err" "$name: error: unknown option '--bogus'"
  # Every error has one form, "TOOL: error: ...", and a bad value one
  # phrasing, "--OPTION: expected ..., found '...'" (README.md).
  "$tool" "$scene" -o "$dir/x.exr" --width 0 2>"$dir/err"; check "--width 0" 2 $?
  message_has "--width 0" "$dir/err" "$name: error: --width: expected an integer from 1 to 65536, found '0'"
  "$tool" "$scene" -o "$dir/x.ro" 2>"$dir/err"; check "bad output name" 2 $?
  message_has "bad output name" "$dir/err" "$name: error: -o '$dir/x.ro' must end in .exr or .png"
  # A directory where no file can be made (/proc even for root) is refused
  # before the work, not after it.
  "$tool" "$scene" -o /proc/x.png 2>"$dir/err"; check "unwritable directory" 2 $?
  message_has "unwritable directory" "$dir/err" "$name: error: -o: "
  grep -q "rendered in" "$dir/err" && { echo "FAIL: rendered before refusing /proc/x.png"; fail=1; }
  # --s begins --stats and at least one more of each renderer's options.
  "$tool" "$scene" -o "$dir/x.exr" --s 1 2>"$dir/err"; check "ambiguous option" 2 $?
  message_has "ambiguous option" "$dir/err" "ambiguous option '--s': it could be --"
  message_has "ambiguous option" "$dir/err" "--stats"
  "$tool" "$scene" -o "$dir/x.exr" --exposure 2>"$dir/err"; check "value missing last" 2 $?
  message_has "value missing last" "$dir/err" "$name: error: --exposure needs a value"
  "$tool" "$dir/missing.json" -o "$dir/x.exr" -q 2>/dev/null; check "missing scene" 2 $?
  "$tool" "$scene" -o "$dir/no/such/x.exr" -q 2>"$dir/err"; check "missing directory" 2 $?
  message_has "missing directory" "$dir/err" "$name: error: -o: directory '$dir/no/such' does not exist"
  [ -e "$dir/no" ] && { echo "FAIL: a missing directory was made without -p"; fail=1; }
  "$tool" "$scene" -o "$dir/made/here/x.exr" -p "$@" 2>"$dir/err"; check "-p" 0 $?
  [ -s "$dir/made/here/x.exr" ] || { echo "FAIL: -p did not write"; fail=1; }
  [ "$(grep -c "rendered in" "$dir/err")" = 1 ] || { echo "FAIL: 'rendered in' not once: $(cat "$dir/err")"; fail=1; }
  iinfo -v "$dir/made/here/x.exr" >"$dir/header"
  for key in Software shafts:tool shafts:version shafts:mode shafts:settings shafts:scene; do
    message_has "EXR provenance" "$dir/header" "$key:"
  done
  message_has "EXR provenance" "$dir/header" "\"$name $("$tool" --version | cut -d' ' -f2)\""
  "$tool" "$scene" -o "$dir/w.exr" -q --width 8 "$@"; check "--width" 0 $?
  iinfo "$dir/w.exr" | grep -Eq "8 x +6," || { echo "FAIL: --width 8: $(iinfo "$dir/w.exr")"; fail=1; }
  "$tool" "$scene" -o "$dir/w.exr" -q --wid=8 "$@"; check "--wid, a prefix of --width" 0 $?
  iinfo "$dir/w.exr" | grep -Eq "8 x +6," || { echo "FAIL: --wid=8: $(iinfo "$dir/w.exr")"; fail=1; }
  "$tool" "$scene" -o "$dir/w.exr" -q --width 10 --height 20 "$@"; check "--width --height" 0 $?
  iinfo "$dir/w.exr" | grep -Eq "10 x +20," || { echo "FAIL: --width 10 --height 20: $(iinfo "$dir/w.exr")"; fail=1; }
  # --crop: the region alone, its place in the settings; a crop that is
  # not inside the image (after --width) is refused with its bound.
  "$tool" "$scene" -o "$dir/c.exr" -q --width 8 --crop 2 1 7 5 "$@"; check "--crop" 0 $?
  iinfo "$dir/c.exr" | grep -Eq "5 x +4," || { echo "FAIL: --crop 2 1 7 5: $(iinfo "$dir/c.exr")"; fail=1; }
  iinfo -v "$dir/c.exr" | grep -q 'crop_x0\\*":2' || { echo "FAIL: --crop not in the settings"; fail=1; }
  "$tool" "$scene" -o "$dir/x.exr" -q --width 8 --crop 0 0 9 6 "$@" 2>"$dir/err"; check "--crop beyond" 2 $?
  message_has "--crop beyond" "$dir/err" "--crop: x1 = 9 is beyond the image's width 8"
  "$tool" "$scene" -o "$dir/x.exr" -q --crop 4 0 4 6 "$@" 2>"$dir/err"; check "--crop empty" 2 $?
  message_has "--crop empty" "$dir/err" "--crop: x1 must be greater than x0"
  "$tool" "$scene" -o "$dir/x.exr" -q --crop 0 0 0 0 "$@" 2>"$dir/err"; check "--crop zeros" 2 $?
  message_has "--crop zeros" "$dir/err" "--crop: the crop 0 0 0 0 is empty"
  "$tool" "$scene" -o "$dir/x.exr" -q --crop 1 2 3 2>"$dir/err"; check "--crop 3 values" 2 $?
  message_has "--crop 3 values" "$dir/err" "--crop needs 4 values"
  [ -e "$dir/x.exr" ] && { echo "FAIL: a refused crop wrote its output"; fail=1; }
  rm -rf "$dir/made" "$dir/w.exr" "$dir/x.exr" "$dir/c.exr"
  parents_undone "$tool" "$scene" -o "$@"
}
# A run with -p that is refused or fails leaves no directory it made, and
# every directory that was there before (issue 11): names too long are
# refused before any is made; a failure after (a scene that does not load,
# a second output refused) removes those made, deepest first.
parents_undone() { # tool, good scene, output option, extra arguments...
  local tool=$1 scene=$2 o=$3 long z
  shift 3
  mkdir -p "$dir/pp/keep"
  z=$(printf 'z%.0s' $(seq 300))
  "$tool" "$scene" $o "$dir/pp/g1/g2/x.exr" $o "$dir/pp/g1/h/$z.png" -p -q "$@" 2>"$dir/err"
  check "-p, a name too long" 2 $?
  message_has "-p, a name too long" "$dir/err" "File name too long"
  long=$dir/pp/g1
  for _ in $(seq 20); do long=$long/$(printf 'd%.0s' $(seq 250)); done
  "$tool" "$scene" $o "$long/x.exr" -p -q "$@" 2>"$dir/err"
  check "-p, a path too long" 2 $?
  message_has "-p, a path too long" "$dir/err" "File name too long"
  "$tool" "$dir/missing.json" $o "$dir/pp/keep/n1/n2/x.exr" -p -q "$@" 2>/dev/null
  check "-p, a scene that does not load" 2 $?
  "$tool" "$scene" $o "$dir/pp/keep/n1/x.exr" $o /proc/x.png -p -q "$@" 2>/dev/null
  check "-p, a second output refused" 2 $?
  [ "$(cd "$dir/pp" && find . | sort | tr '\n' ' ')" = ". ./keep " ] \
    || { echo "FAIL: -p runs refused left: $(cd "$dir/pp" && find .)"; fail=1; }
  rm -rf "$dir/pp"
}
# No output may be an input or another output of the run, whatever the
# spelling; a refused run exits 2 and changes nothing; a run killed by
# SIGINT, SIGTERM or SIGKILL while rendering leaves no file of any name.
render_files_distinct() { # tool, good scene, extra arguments...
  local tool=$1 scene=$2 sdir sname
  shift 2
  sdir=$(dirname "$scene"); sname=$(basename "$scene")
  cp "$scene" "$dir/keep.json"
  "$tool" "$scene" -o "$dir/x.exr" --stats "$scene" -q "$@" 2>"$dir/err"
  check "--stats is the scene" 2 $?
  message_has "--stats is the scene" "$dir/err" "must not overwrite an input"
  "$tool" "$scene" -o "$dir/x.exr" --stats "$sdir/./$sname" -q "$@" 2>/dev/null
  check "--stats is the scene, spelled ./" 2 $?
  ln -s "$scene" "$dir/link.json"
  "$tool" "$scene" -o "$dir/x.exr" --stats "$dir/link.json" -q "$@" 2>/dev/null
  check "--stats is a link to the scene" 2 $?
  rm -f "$dir/link.json"
  "$tool" "$scene" -o "$dir/x.exr" --stats "$dir/sub/../x.exr" -p -q "$@" 2>"$dir/err"
  check "--stats is -o" 2 $?
  message_has "--stats is -o" "$dir/err" "each output of a run must be a file of its own"
  "$tool" "$scene" -o "$dir/x.exr" -o "$dir/x.exr" -q "$@" 2>/dev/null
  check "-o twice" 2 $?
  mkdir -p "$dir/adir"
  "$tool" "$scene" -o "$dir/x.exr" --stats "$dir/adir" -q "$@" 2>"$dir/err"
  check "--stats is a directory" 2 $?
  message_has "--stats is a directory" "$dir/err" "not a regular file"
  rmdir "$dir/adir"
  cmp -s "$scene" "$dir/keep.json" || { echo "FAIL: the scene was changed"; fail=1; }
  [ -e "$dir/x.exr" ] && { echo "FAIL: a refused run wrote x.exr"; fail=1; }
  [ -n "$(ls -A "$sdir" "$dir" | grep '^\.')" ] && { echo "FAIL: refused runs left: $(ls -A "$sdir" "$dir")"; fail=1; }
  rm -f "$dir/keep.json"; rmdir "$dir/sub" 2>/dev/null
  # A scene that is no regular file is refused at once, not read forever.
  timeout 20 "$tool" /dev/zero -o "$dir/x.exr" -q "$@" 2>"$dir/err"; check "/dev/zero as the scene" 2 $?
  message_has "/dev/zero as the scene" "$dir/err" "it is a character device, not a regular file"
}
# Interrupts a run with each signal once its output is open: the run ends
# by the signal and its directory is as before (no output, no temporary).
render_signals() { # tool, slow scene, extra arguments...
  local tool=$1 scene=$2 sig pid status sub
  shift 2
  mkdir -p "$dir/sig"
  for sig in INT TERM KILL; do
    # A shell starts background jobs with SIGINT ignored: undone first.
    # With -p, the directories made go too (SIGKILL cannot be caught).
    [ $sig = KILL ] && sub= || sub=made/by/p/
    python3 -c 'import os, signal, sys
signal.signal(signal.SIGINT, signal.SIG_DFL)
os.execvp(sys.argv[1], sys.argv[1:])' "$tool" "$scene" -o "$dir/sig/${sub}s.exr" \
      -o "$dir/sig/${sub}s.png" --stats "$dir/sig/${sub}s.json" -p -q "$@" 2>/dev/null &
    pid=$!
    # Once the tool runs (not python), well into the render.
    while [ "$(readlink /proc/$pid/exe)" != "$(readlink -f "$tool")" ] && kill -0 $pid 2>/dev/null; do
      sleep 0.05
    done
    sleep 0.5
    kill -s $sig $pid
    wait $pid; status=$?
    [ $status -gt 128 ] || { echo "FAIL: SIG$sig: the run ended with $status, not by the signal (too fast a scene?)"; fail=1; }
    empty "a run killed by SIG$sig" "$dir/sig"
  done
  rm -rf "$dir/sig"
}
# Writes the tests' small scene: a quad floor in a medium box, seen from
# (0, 1, 5). The light is on line 6 (messages name it).
basic_scene() { # file, width, height, light (JSON), more shapes, more keys
  cat >"$1" <<JSON
{"format": "shafts-scene", "version": 1,
 "camera": {"position": [0, 1, 5], "look_at": [0, 0.5, 0], "fov_y_deg": 45,
            "width": $2, "height": $3},
 "medium": {"sigma_s": [0.1, 0.1, 0.1],
            "bounds": {"min": [-3, 0, -3], "max": [3, 3, 3]}},
 "lights": [$4],
 "materials": {"floor": {"diffuse": [0.5, 0.5, 0.5]}},
 "shapes": [{"type": "quad", "material": "floor", "corner": [-3, 0, 3],
             "u": [6, 0, 0], "v": [0, 0, -6]}${5:-}]${6:-}}
JSON
}
POINT_LIGHT='{"type": "point", "position": [0, 2, 0], "intensity": [5, 5, 5]}'
# A number no renderer can hold, put into the good scene by a sed
# expression, is refused with 2 and a located message naming the key.
huge_refused() { # tool, good scene, sed expression, key (a regex)
  sed "$3" "$2" >"$dir/huge.json"
  "$1" "$dir/huge.json" -o "$dir/x.exr" -q 2>"$dir/err"; check "huge value $4" 2 $?
  grep -q "huge.json:[0-9]*:[0-9]*: $4" "$dir/err" \
    || { echo "FAIL: huge-value message: $(cat "$dir/err")"; fail=1; }
}
# basic_scene's scene with its medium turned into height fog (issue 12).
height_fog_scene() { # good scene, new file
  sed 's/"medium": {"sigma_s"/"medium": {"type": "height_fog", "scale_height": 1, "sigma_s"/' \
    "$1" >"$2"
}
# A tool that renders homogeneous media only refuses height fog with 2, a
# message located at medium.type naming the medium's type, and no output.
height_fog_refused() { # good scene, what, command... (the output is $dir/fog_out.*)
  local good=$1 what=$2; shift 2
  height_fog_scene "$good" "$dir/fog.json"
  "$@" >/dev/null 2>"$dir/err"; check "$what refuses height fog" 2 $?
  grep -q "fog.json:[0-9]*:21: medium.type: .*not a medium of type 'height_fog'" "$dir/err" \
    || { echo "FAIL: $what height-fog message: $(cat "$dir/err")"; fail=1; }
  ls "$dir" | grep -q '^fog_out' && { echo "FAIL: $what wrote an output"; fail=1; }
  rm -f "$dir/fog.json"
}
# The camera at a point light inside the medium (issue 11): a warning
# naming the light and the convention's distance, exit 0, finite output.
camera_at_light_warns() { # tool
  basic_scene "$dir/at_light.json" 8 6 \
    '{"type": "point", "position": [0, 1, 2], "intensity": [5, 5, 5]}'
  sed -i 's/"position": \[0, 1, 5\], "look_at"/"position": [0, 1, 2], "look_at"/' "$dir/at_light.json"
  "$1" "$dir/at_light.json" -o "$dir/at_light.exr" 2>"$dir/err"
  check "camera at a light" 0 $?
  grep -q "warning: the camera is at lights\[0\] inside the medium.*no nearer than 0.0009 " \
    "$dir/err" || { echo "FAIL: camera-at-light warning: $(cat "$dir/err")"; fail=1; }
  rm -f "$dir/at_light.json" "$dir/at_light.exr"
}
# A misspelled key (with its place and a suggestion), a truncated file and
# numbers out of range are refused with 2, and nothing is left behind.
bad_scenes_refused() { # tool, good scene (basic_scene's: the light on line 6)
  sed 's/"intensity": \[5, 5, 5\]/"intensty": [5, 5, 5]/' "$2" >"$dir/typo.json"
  printf '{"format": "shafts-scene", "version": 1, "camera": {' >"$dir/truncated.json"
  "$1" "$dir/typo.json" -o "$dir/x.exr" -q 2>"$dir/err"; check "misspelled key" 2 $?
  grep -q "typo.json:6:.*lights\[0\].*did you mean 'intensity'" "$dir/err" \
    || { echo "FAIL: misspelled-key message: $(cat "$dir/err")"; fail=1; }
  "$1" "$dir/truncated.json" -o "$dir/x.exr" -q 2>/dev/null; check "truncated" 2 $?
  # Numbers that are valid JSON but that no renderer can hold: a located
  # error naming the key (issue 11, non-finite and out-of-range values).
  huge_refused "$1" "$2" 's/"intensity": \[5, 5, 5\]/"intensity": [1e300, 5, 5]/' 'lights\[0\]\.intensity\[0\]'
  huge_refused "$1" "$2" 's/"sigma_s": \[0.1, 0.1, 0.1\]/"sigma_s": [1.7e308, 0.1, 0.1]/' 'medium\.sigma_s\[0\]'
  huge_refused "$1" "$2" 's/"fov_y_deg": 45/"fov_y_deg": 1e-300/' 'camera\.fov_y_deg'
  # A mesh file that is missing, outside the scene's directory or named by
  # an absolute path: 2 (not 1, though the library's status is SH_ERR_IO
  # for a missing file), the key and what was expected in the message.
  mkdir -p "$dir/sub"
  printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' >"$dir/tri.obj"
  local mesh='{"type": "mesh", "material": "floor", "file": "%s"}'
  basic_scene "$dir/sub/nomesh.json" 8 6 "$POINT_LIGHT" ", $(printf "$mesh" no_such.obj)"
  "$1" "$dir/sub/nomesh.json" -o "$dir/x.exr" -q 2>"$dir/err"; check "missing mesh" 2 $?
  message_has "missing mesh" "$dir/err" "shapes[1].file: cannot open the mesh file 'no_such.obj' (resolved to '$dir/sub/no_such.obj')"
  basic_scene "$dir/sub/outside.json" 8 6 "$POINT_LIGHT" ", $(printf "$mesh" ../tri.obj)"
  "$1" "$dir/sub/outside.json" -o "$dir/x.exr" -q 2>"$dir/err"; check "mesh outside the scene's directory" 2 $?
  message_has "mesh outside the scene's directory" "$dir/err" "outside the scene's directory"
  basic_scene "$dir/sub/absolute.json" 8 6 "$POINT_LIGHT" ", $(printf "$mesh" "$dir/tri.obj")"
  "$1" "$dir/sub/absolute.json" -o "$dir/x.exr" -q 2>"$dir/err"; check "absolute mesh name" 2 $?
  message_has "absolute mesh name" "$dir/err" "shapes[1].file: the file name '$dir/tri.obj' is absolute"
  rm -rf "$dir/sub" "$dir/tri.obj"
  [ -e "$dir/x.exr" ] && { echo "FAIL: an output was written after an error"; fail=1; }
  ls "$dir" | grep -q tmp && { echo "FAIL: a temporary file was left"; fail=1; }
}
