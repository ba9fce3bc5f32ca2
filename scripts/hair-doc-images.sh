#!/usr/bin/env bash
# Renders the pictures of docs/hairs.md from the examples in models/hair-modules: one headless
# PNG per module example, and POV-Ray renders where the preview cannot show the module (radius)
# or to show the hairs as POV-Ray draws them.
#   scripts/hair-doc-images.sh [BUILD_DIR]      (default build/release)
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build/release}"
hirsute="$build/cli/hirsute"
examples=models/hair-modules
out=docs/images/hairs
mkdir -p "$out"
for l in "$examples"/*.l; do
  name=$(basename "$l" .l)
  case "$name" in straight | curly) continue ;; esac  # the template hairs
  view="$examples/$name.v"
  size=600x500
  [ -f "$view" ] || { view="$examples/hair-modules.v"; size=800x300; }
  "$hirsute" render "$l" "$view" -o "$out/$name.png" --size "$size"
done
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for name in radius density; do
  "$hirsute" export "$examples/$name.l" "$examples/hair-modules.v" --pov "$work/$name.pov" \
    --render --size 800x300
  cp "$work/$name.png" "$out/$name-pov.png"
done
