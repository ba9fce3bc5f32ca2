#!/usr/bin/env bash
# Renders the pictures of docs/fur.md and of the fur models' READMEs: each model headless, dry
# and wet, and the furry square's word through POV-Ray (when povray is on the PATH).
#   HIRSUTE=path/to/hirsute scripts/fur-doc-images.sh   (default build/release/cli/hirsute)
set -euo pipefail
cd "$(dirname "$0")/.."
hirsute="$(realpath "${HIRSUTE:-build/release/cli/hirsute}")"
out="$(pwd)/docs/images/fur"
mkdir -p "$out"
render() {  # folder lsystem view picture size
  (cd "models/$1" && "$hirsute" render "$2" "$3" -o "$out/$4.png" --size "$5")
}
render fur-torus torus.l torus.v torus 640x480
render fur-torus torus.l wet.v torus-wet 640x480
render fur-square square.l square.v square 520x440
render fur-square square.l word.v word 520x440
render fur-curls curls.l curls.v curls 1000x380
render pussy-willow pussy-willow.l pussy-willow.v pussy-willow 560x560
render pussy-willow pussy-willow.l wet.v pussy-willow-wet 560x560
render fur-lambs-ear lambs-ear.l lambs-ear.v lambs-ear 560x470
(cd models/fur-lambs-ear && "$hirsute" render lambs-ear.l lambs-ear.v --droplets 60 \
  --droplet-radius 0.14 -o "$out/lambs-ear-wet.png" --size 560x470)
if command -v povray >/dev/null; then
  work="$(mktemp -d)"
  trap 'rm -rf "$work"' EXIT
  (cd models/fur-square && "$hirsute" export square.l word.v --pov "$work/word.pov" --render \
    --size 520x440)
  cp "$work/word.png" "$out/word-povray.png"
fi
# Fur over time (docs/fur.md, "Over time"): the square in a gusty wind, six droplets at frame 2,
# drying from frame 24; frames 1, 24 and 48 through POV-Ray.
if command -v povray >/dev/null; then
  (cd models/fur-square && "$hirsute" simulate square.l square.v -o "$work/frames" --frames 48 \
    --wind 3 0 0 --gusts 1 --drop 2:6:0.08 --dry 1 --dry-from 24 --size 320x240)
  for k in 0001 0024 0048; do
    povray -D +A +W320 +H240 "$work/frames/frame-$k.pov" +O"$out/simulate-$k.png" 2>/dev/null
  done
fi
