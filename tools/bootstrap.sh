#!/usr/bin/env bash
# Installs the Debian packages the project builds, tests and validates with.
# Idempotent: packages already present are not touched, and nothing is
# downloaded from outside Debian's archive.
#   tools/bootstrap.sh          everything: build, test and validation (the
#                               tests render with POV-Ray and Blender too)
#   tools/bootstrap.sh --build  only what the build needs (not the GL
#                               libraries gl_shafts loads when it renders)
#   tools/bootstrap.sh --slurm  only Slurm and munge (tools/slurm_local.sh)
set -eu

# gl_shafts builds with the Khronos headers only (libegl-dev, libgl-dev) and
# loads its GL at run time: EGL through libglvnd with Mesa's driver (llvmpipe
# where there is no GPU), or OSMesa as the fallback (gl_shafts/gs_context.h).
build_pkgs="build-essential cmake pkg-config libjansson-dev libembree-dev
  libegl-dev libgl-dev libopenexr-dev libpng-dev libopenimageio-dev openimageio-tools libassimp-dev python3 python3-numpy"
# make fuzz: clang with libFuzzer (Debian's clang carries it).
fuzz_pkgs="clang"
gl_pkgs="libegl1 libegl-mesa0 libgl1-mesa-dri libosmesa6"
peer_pkgs="povray blender xvfb xauth"
# The validation's Slurm executor and its single-node test cluster
# (tools/slurm_local.sh): Debian 12's slurm-wlm 22.05 without the GUI.
slurm_pkgs="slurmctld slurmd slurm-client munge"

want="$build_pkgs $gl_pkgs $peer_pkgs $slurm_pkgs $fuzz_pkgs"
for arg in "$@"; do
  case "$arg" in
    --build) want="$build_pkgs" ;;
    --slurm) want="$slurm_pkgs" ;;
    -h|--help) sed -n '2,9p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "bootstrap: unknown option '$arg'" >&2; exit 2 ;;
  esac
done

missing=""
for p in $want; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing="$missing $p"
  fi
done
[ -z "$missing" ] && exit 0

echo "bootstrap: installing:$missing" >&2
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
# shellcheck disable=SC2086
$sudo apt-get install -y -qq --no-install-recommends $missing >/dev/null
