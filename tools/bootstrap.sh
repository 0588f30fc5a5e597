#!/usr/bin/env bash
# Installs the Debian packages the project builds, tests and validates with.
# Idempotent: packages already present are not touched, and nothing is
# downloaded from outside Debian's archive.
#   tools/bootstrap.sh          everything: build, test and validation (the
#                               tests render with POV-Ray and Blender too)
#   tools/bootstrap.sh --build  only what the build needs
set -eu

build_pkgs="build-essential cmake pkg-config libjansson-dev libembree-dev
  libosmesa6-dev libopenimageio-dev openimageio-tools libassimp-dev python3 python3-numpy"
peer_pkgs="povray blender xvfb xauth"

want="$build_pkgs $peer_pkgs"
for arg in "$@"; do
  case "$arg" in
    --build) want="$build_pkgs" ;;
    -h|--help) sed -n '2,7p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
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
