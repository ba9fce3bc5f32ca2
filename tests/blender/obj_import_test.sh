#!/usr/bin/env bash
# The hairy leaf's OBJ (3 663 hairs as `l` elements) read by both of Blender's OBJ importers,
# headless: each keeps every segment of every polyline (check_obj_import.py). Skipped (exit 77)
# where Blender is not installed: `apt-get install --no-install-recommends blender`.
#
#   obj_import_test.sh HIRSUTE SOURCE_DIR
set -euo pipefail
hirsute=$1
source=$2
if ! command -v blender > /dev/null; then
  echo "SKIPPED: blender is not installed, so the OBJ's import into Blender is not tested" \
    "(apt-get install --no-install-recommends blender)"
  exit 77
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
leaf=$source/models/hairy-leaf
"$hirsute" export "$leaf/hairy-leaf.l" "$leaf/hairy-leaf.v" --obj "$work/leaf.obj"
# The segments of the file's `l` elements: each element of n vertices has n - 1.
segments=$(awk '$1 == "l" { n += NF - 2 } END { print n }' "$work/leaf.obj")
test "$segments" -gt 10000
timeout -k 10 300 blender -b --factory-startup --python-exit-code 1 \
  --python "$source/tests/blender/check_obj_import.py" -- "$work/leaf.obj" "$segments" 2>&1 |
  grep -E '^(ok|FAILED)|Error'
