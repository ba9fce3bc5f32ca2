#!/usr/bin/env bash
# Renders the pictures of docs/tutorial.md by the tutorial's own commands, run in a scratch
# folder that holds a copy of models/tutorial, and copies them into docs/images/tutorial.
#   scripts/tutorial-images.sh [BUILD_DIR]      (default build/release)
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
build="${1:-build/release}"
case "$build" in /*) ;; *) build="$root/$build" ;; esac
hirsute() { "$build/cli/hirsute" "$@"; }
out="$root/docs/images/tutorial"
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/models"
cp -r models/tutorial "$work/models/"
cd "$work"
for n in 1 2 3 4; do
  hirsute render models/tutorial/plant-$n.l models/tutorial/tutorial.v -o plant-$n.png --size 480x360
done
hirsute render models/tutorial/plant-5.l models/tutorial/hairy.v -o plant-5.png --size 480x360
hirsute render models/tutorial/plant-5.l models/tutorial/still.v --trace --spp 24 --size 480x360 -o still.png
hirsute export models/tutorial/plant-5.l models/tutorial/hairy.v --pov plant.pov --render --size 480x360
hirsute export models/tutorial/plant-5.l models/tutorial/still.v --pov still-pov.pov --trace-lights --render --size 480x360
cp plant-1.png plant-2.png plant-3.png plant-4.png plant-5.png still.png "$out/"
cp plant.png "$out/plant-pov.png"
cp still-pov.png "$out/still-pov.png"
