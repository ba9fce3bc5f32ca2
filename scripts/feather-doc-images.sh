#!/usr/bin/env bash
# Renders the pictures of docs/feathers.md, "Examples", from the models in
# models/feather-parameters: one headless PNG per model, each with the view of the same name;
# and those of "Feather types from scans" from models/feather-scan.
#   HIRSUTE=path/to/hirsute scripts/feather-doc-images.sh   (default build/release/cli/hirsute)
set -euo pipefail
cd "$(dirname "$0")/.."
hirsute="$(realpath "${HIRSUTE:-build/release/cli/hirsute}")"
examples=models/feather-parameters
out=docs/images/feathers/params
mkdir -p "$out"
for l in "$examples"/*.l; do
  name=$(basename "$l" .l)
  size=900x300
  [ "$name" = seed ] && size=600x300  # two feathers only
  "$hirsute" render "$l" "$examples/$name.v" -o "$out/$name.png" --size "$size"
done
# material: needs a material file, so its example has a folder of its own.
"$hirsute" render models/feather-material/feather-material.l \
  models/feather-material/feather-material.v -o "$out/material.png" --size 900x300
# Feather types from scans: the hawk drawn flat as a scan, read back, drawn again.
(cd models/feather-scan && "$hirsute" render scan.l feather-scan.v -o hawk-scan.png --size 600x1000 &&
  "$hirsute" feather-scan hawk-scan.png -o found.fea --length 12.5 --texture found-vane.png &&
  "$hirsute" render scan.l feather-scan.v -o ../../docs/images/feathers/scan-hawk.png --size 360x600 &&
  "$hirsute" render found.l feather-scan.v -o ../../docs/images/feathers/scan-found.png --size 360x600)
