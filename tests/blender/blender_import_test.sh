#!/usr/bin/env bash
# The oriental poppy through `hirsute export --blender` and the add-on blender/hirsute_import.py,
# in Debian's Blender run headless: the add-on's command line imports, saves and renders it in
# Cycles at 96x72, and check_import.py counts its hair curves against the hairs' table, checks
# the camera frames the plant and finds the hairs in the render; installed from the preferences
# the add-on's operator imports it too; a file cut short is refused.
# Skipped (exit 77) where Blender is not installed: `apt-get install --no-install-recommends
# blender` (Debian 12: Blender 3.4).
#
#   blender_import_test.sh HIRSUTE SOURCE_DIR
set -euo pipefail
hirsute=$1
source=$2
if ! command -v blender > /dev/null; then
  echo "SKIPPED: blender is not installed, so the import into Blender is not tested" \
    "(apt-get install --no-install-recommends blender)"
  exit 77
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
poppy=$source/models/oriental-poppy
"$hirsute" export "$poppy/oriental-poppy.l" "$poppy/oriental-poppy.v" \
  --blender "$work/poppy.hirsute" --hairs "$work/poppy.csv" --size 96x72
hairs=$(($(wc -l < "$work/poppy.csv") - 1))

# Blender's own start-up files are left out (--factory-startup); a Python error fails the run.
blender=(timeout -k 10 300 blender -b --factory-startup --python-exit-code 1)
"${blender[@]}" --python "$source/blender/hirsute_import.py" -- "$work/poppy.hirsute" \
  --save "$work/poppy.blend" --render "$work/poppy.png" --samples 8 > "$work/import.log" 2>&1 ||
  { cat "$work/import.log"; exit 1; }
test -s "$work/poppy.blend"
"${blender[@]}" --python "$source/tests/blender/check_import.py" -- \
  "$source/blender/hirsute_import.py" "$work/poppy.hirsute" "$hairs" "$work/poppy.png" 2>&1 |
  grep -v '^Fra:'

# Installed as Blender's preferences install an add-on (into a scratch user folder), its import
# operator builds the scene too.
BLENDER_USER_SCRIPTS=$work/scripts BLENDER_USER_CONFIG=$work/config "${blender[@]}" \
  --python "$source/tests/blender/check_addon_install.py" -- \
  "$source/blender/hirsute_import.py" "$work/poppy.hirsute" 2>&1 | grep -E '^(ok|FAILED)|Error'

# A file cut short is refused with a message and exit code 2, not read past its end.
head -c 100000 "$work/poppy.hirsute" > "$work/cut.hirsute"
status=0
"${blender[@]}" --python "$source/blender/hirsute_import.py" -- "$work/cut.hirsute" \
  > "$work/cut.log" 2>&1 || status=$?
if [ "$status" -ne 2 ] ||
  ! grep -q "cut.hirsute: not a Hirsute scene for Blender" "$work/cut.log"; then
  echo "FAILED: a file cut short: exit code $status"
  grep -v '^Fra:' "$work/cut.log"
  exit 1
fi
echo "ok: a file cut short is refused (exit code 2)"
