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
