#!/usr/bin/env bash
# Runs the light meshes benchmark and prints its tables (docs/lmm.md quotes
# them). Usage: lmm_tracer/bench.sh [BUILD_DIR] [--quick]
set -eu
build=${1:-build}
shift || true
cmake --build "$build" --target lmm_bench -j "$(nproc)" >/dev/null
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
echo "date: $(date -u +%Y-%m-%d)"
echo
SHAFTS_SOURCE_DIR=$(cd "$(dirname "$0")/.." && pwd) "$build/lmm_tracer/lmm_bench" "$@"
