#!/usr/bin/env bash
# Renders the pictures of docs/dynamics.md and of the simulated models' READMEs: frames of
# `hirsute simulate` through POV-Ray (which must be on the PATH).
#   HIRSUTE=path/to/hirsute scripts/dynamics-doc-images.sh   (default build/release/cli/hirsute)
set -euo pipefail
cd "$(dirname "$0")/.."
hirsute="$(realpath "${HIRSUTE:-build/release/cli/hirsute}")"
out="$(pwd)/docs/images/dynamics"
mkdir -p "$out"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
# simulate folder "files" width height frames picture frame…
simulate() {
  local folder="$1" files="$2" width="$3" height="$4" frames="$5" picture="$6"
  shift 6
  # shellcheck disable=SC2086
  (cd "models/$folder" && "$hirsute" simulate $files -o "$work/$picture" --frames "$frames" \
    --size "${width}x${height}")
  for frame in "$@"; do
    local name
    name="$(printf 'frame-%04d' "$frame")"
    povray +I"$work/$picture/$name.pov" +O"$out/$picture-$(printf '%02d' "$frame").png" \
      +W"$width" +H"$height" +A0.3 -D -V >/dev/null 2>&1
  done
}
simulate coat-bending "bending.l bending.v bending.a" 400 300 25 coat-bending 1 13 25
simulate bird-wing "bird-wing.l bird-wing.v bird-wing.a" 400 300 37 bird-wing 1 7 37
simulate feather-grass "feather-grass.l wind.v" 360 360 48 feather-grass-wind 1 24 48
