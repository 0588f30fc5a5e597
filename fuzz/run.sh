#!/usr/bin/env bash
# Runs the libFuzzer harnesses of a SHAFTS_FUZZ build (docs/fuzzing.md):
# each for SECONDS, starting from its committed seeds (fuzz/corpus/NAME,
# copied into BUILD/fuzz-corpus/NAME, where what the fuzzer finds stays for
# the next run; the committed corpus is never written), the scene parser
# with the dictionary fuzz/scene.dict. A crash, leak, timeout or UBSan
# report stops the run: its input goes to BUILD/fuzz-artifacts/ and the
# exit status is 1.
#   fuzz/run.sh BUILD SECONDS     (make fuzz; make fuzz FUZZ_SECONDS=20 in CI)
set -eu
build=$1 seconds=$2
src=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$build/fuzz-artifacts"
export LSAN_OPTIONS="suppressions=$src/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
status=0
for h in scene mesh; do
  corpus=$build/fuzz-corpus/$h
  mkdir -p "$corpus"
  cp -n "$src/corpus/$h/"* "$corpus/"
  dict=()
  [ -f "$src/$h.dict" ] && dict=(-dict="$src/$h.dict")
  echo "fuzz: $h for $seconds s" >&2
  if ! "$build/fuzz/${h}_fuzz" "$corpus" "${dict[@]}" -max_total_time="$seconds" \
       -timeout=10 -rss_limit_mb=2048 -max_len=65536 -print_final_stats=1 \
       -artifact_prefix="$build/fuzz-artifacts/$h-" 2>"$build/fuzz-$h.log"; then
    tail -40 "$build/fuzz-$h.log" >&2
    echo "fuzz: $h: a fault (input in $build/fuzz-artifacts/)" >&2
    status=1
  else
    grep -E "stat::number_of_executed_units|cov:" "$build/fuzz-$h.log" | tail -2 >&2
  fi
done
exit $status
