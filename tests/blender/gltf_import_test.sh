#!/usr/bin/env bash
# The herb's surfaces as glTF (.gltf with its buffer, and .glb) opened by Blender's own glTF
# importer, headless: its meshes and spheres, their triangles and colours, and the view file's camera
# looking at them (check_gltf_import.py). Skipped (exit 77) where Blender, or the numpy its glTF
# importer needs, is not installed.
#
#   gltf_import_test.sh HIRSUTE SOURCE_DIR
set -euo pipefail
hirsute=$1
source=$2
if ! command -v blender > /dev/null; then
  echo "SKIPPED: blender is not installed, so the glTF's import into Blender is not tested" \
    "(apt-get install --no-install-recommends blender python3-numpy)"
  exit 77
fi
if ! blender -b --factory-startup --python-exit-code 1 --python-expr 'import numpy' \
  > /dev/null 2>&1; then
  echo "SKIPPED: Blender's glTF importer needs numpy (apt-get install python3-numpy)"
  exit 77
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
herb=$source/models/herb
"$hirsute" export "$herb/herb.l" "$herb/herb.v" --size 64x48 --gltf "$work/herb.gltf" \
  --obj "$work/herb.obj"
# The OBJ's meshes before its spheres: objects, and triangles whose corners are three different
# points (Blender's importer drops the others, which have no area); then its spheres, which the
# glTF has as one mesh a colour, each sphere 120 triangles (the OBJ's 224).
read -r meshes triangles < <(awk '/^o / { spheres = ($2 == "spheres") }
  /^o / && !spheres { o++ } /^v / { v[++n] = $2 " " $3 " " $4 }
  spheres && /^usemtl / && !($2 in colours) { colours[$2] = 1; o++ }
  spheres && /^f / { s++ }
  !spheres && /^f / { split($2, a, "/"); split($3, b, "/"); split($4, c, "/")
          if (v[a[1]] != v[b[1]] && v[b[1]] != v[c[1]] && v[a[1]] != v[c[1]]) f++ }
  END { print o, f + s / 224 * 120 }' "$work/herb.obj")
test "$triangles" -gt 1000
"$hirsute" export "$herb/herb.l" "$herb/herb.v" --size 64x48 --gltf "$work/herb.glb"
for file in "$work/herb.gltf" "$work/herb.glb"; do
  timeout -k 10 300 blender -b --factory-startup --python-exit-code 1 \
    --python "$source/tests/blender/check_gltf_import.py" -- "$file" "$meshes" "$triangles" 2>&1 |
    grep -E '^(ok|FAILED)|Error'
done
