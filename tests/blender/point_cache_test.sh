#!/usr/bin/env bash
# The feather grass simulated for three frames with `--pc2` and `--obj`, and the point cache
# played in Debian's Blender, headless, by the add-on (blender/hirsute_import.py: the base mesh
# through Blender's OBJ importer, the cache through the Mesh Cache modifier): every frame's
# vertices are that frame's OBJ's (check_point_cache.py). Skipped (exit 77) where Blender is not
# installed: `apt-get install --no-install-recommends blender`.
#
#   point_cache_test.sh HIRSUTE SOURCE_DIR
set -euo pipefail
hirsute=$1
source=$2
if ! command -v blender > /dev/null; then
  echo "SKIPPED: blender is not installed, so the point cache's import into Blender is not" \
    "tested (apt-get install --no-install-recommends blender)"
  exit 77
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
grass=$source/models/feather-grass
"$hirsute" simulate "$grass/feather-grass.l" "$grass/wind.v" -o "$work/frames" --frames 3 \
  --obj --size 32x24 --pc2 "$work/grass.pc2" > /dev/null
timeout -k 10 300 blender -b --factory-startup --python-exit-code 1 \
  --python "$source/tests/blender/check_point_cache.py" -- "$source/blender/hirsute_import.py" \
  "$work/grass.pc2" "$work"/frames/frame-000{1,2,3}.obj 2>&1 | grep -E '^(ok|FAILED)|Error'
