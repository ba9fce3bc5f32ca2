#!/usr/bin/env bash
# An organ is one folder and one line (docs/design.md, "Adding an organ"): outside its folder
# (hairs/NAME/ with its headers in hairs/include/hirsute/hairs/NAME/) and the registry's list
# (hairs/organs/organ_list.h), no source or build file of the program includes an organ's header
# or links an organ's library. The organs are read from the list itself, so a new organ is
# checked as soon as it is registered; a file that starts naming an organ fails the test.
#
#   organ_folders.sh SOURCE_DIR
#
# Prints what adding an organ touches, then every line that names an organ where it should not.
# Files still waiting to move into their organ's folder are listed in `pending` below, each with
# what it holds; one that no longer names an organ fails too, so that the list only shrinks.
set -euo pipefail

root=${1:?usage: organ_folders.sh SOURCE_DIR}
cd "$root"
list=hairs/organs/organ_list.h

# Organ code that has not reached its folder yet: the commands that move, bench and scan organs,
# the feathers' vertex data shared by the outputs, and the feather coat's dynamics (which the
# fur's motion also uses).
pending=(
  cli/CMakeLists.txt
  cli/bench_command.cpp
  cli/feather_scan_command.cpp
  cli/simulate_command.cpp
  viewer/view/CMakeLists.txt
  viewer/view/feather_buffers.cpp
  viewer/include/hirsute/viewer/view/feather_buffers.h
  hairs/dynamics/CMakeLists.txt
  hairs/dynamics/coat_motion.cpp
  hairs/dynamics/coat_shingling.cpp
  hairs/dynamics/feather_coat_simulation.cpp
  hairs/dynamics/feather_poses.cpp
  hairs/dynamics/feather_stem.cpp
  hairs/include/hirsute/hairs/dynamics/coat_motion.h
  hairs/include/hirsute/hairs/dynamics/coat_runner.h
  hairs/include/hirsute/hairs/dynamics/feather_poses.h
  hairs/include/hirsute/hairs/dynamics/feather_stem.h
)

folders=()
while read -r folder; do
  folders+=("$folder")
done < <(sed -nE 's/^ *HIRSUTE_ORGAN_ENTRY\(([a-z_]+), *[A-Za-z]+\).*/\1/p' "$list")
if [ ${#folders[@]} -eq 0 ]; then
  echo "$list: no HIRSUTE_ORGAN_ENTRY line" >&2
  exit 1
fi

# What names an organ: an include of its headers, or one of the libraries its folder builds.
patterns=()
for folder in "${folders[@]}"; do
  [ -d "hairs/$folder" ] || { echo "$list: no folder hairs/$folder" >&2; exit 1; }
  patterns+=("hirsute/hairs/$folder/")
  while read -r library; do
    patterns+=("\\b$library\\b")
  done < <(find "hairs/$folder" -name CMakeLists.txt -exec \
    sed -nE 's/^add_library\((hirsute_[a-z_]+).*/\1/p' {} +)
done
pattern=$(IFS='|'; echo "${patterns[*]}")

echo "Adding an organ touches:"
echo "  hairs/NAME/ (its CMakeLists.txt and those of export/, gl/, live/, trace/)"
echo "  hairs/include/hirsute/hairs/NAME/"
echo "  one HIRSUTE_ORGAN_ENTRY line in $list"
echo "  its documentation (docs/NAME.md) and its tests, fixtures and benchmarks"
echo "Registered: ${folders[*]}"

# The program's shared layers: everything but the organs' own folders and the registry's list.
mapfile -t files < <(find core lsys interpreter environment viewer cli hairs CMakeLists.txt -type f \
  \( -name '*.h' -o -name '*.cpp' -o -name '*.c' -o -name CMakeLists.txt \) | sort |
  grep -vxF "$list" |
  grep -vE "^hairs/($(IFS='|'; echo "${folders[*]}"))/|^hairs/include/hirsute/hairs/($(IFS='|'; echo "${folders[*]}"))/|^hairs/CMakeLists\.txt$")

status=0
for file in "${files[@]}"; do
  [ -f "$file" ] || continue
  waiting=0
  for p in "${pending[@]}"; do [ "$p" = "$file" ] && waiting=1; done
  if hits=$(grep -nE "$pattern" "$file"); then
    if [ $waiting = 0 ]; then
      echo "$file names an organ outside its folder:" >&2
      printf '  %s\n' "$hits" >&2
      status=1
    fi
  elif [ $waiting = 1 ]; then
    echo "$file no longer names an organ: take it off the pending list of $0" >&2
    status=1
  fi
done
for p in "${pending[@]}"; do
  [ -f "$p" ] || { echo "$p is gone: take it off the pending list of $0" >&2; status=1; }
done
exit $status
