#!/usr/bin/env bash
# Prints a SHA-256 digest of every output of every command on every model of models/ (and of the
# cpfg conformance set in ../shared/conformance when it is there): the derived string, the
# POV-Ray scene, the OBJ and its material library, the hair and feather tables and a small PNG.
# Run it before and after a change that must not change what users get, and compare:
#
#   scripts/output-digests.sh > before.txt      # on the commit before
#   scripts/output-digests.sh > after.txt       # on the change
#   diff before.txt after.txt                   # no line: every output is byte-identical
#
#   HIRSUTE=path/to/hirsute  (default build/release/cli/hirsute)
#   RENDER=0                 leaves the PNGs out (they take most of the time)
#
# A model X.l is run with X.v beside it, else with the folder's only view file; a view file that
# no .l is named after is run with the folder's only .l. X.e beside it is its environment.
# Runs that fail print their exit code in place of the digests, so a change in failures shows too.
set -uo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
hirsute=${HIRSUTE:-$root/build/release/cli/hirsute}
render=${RENDER:-1}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

digest() {  # digest LABEL FILE…: one line per file that exists
  local label=$1 file
  shift
  for file in "$@"; do
    [ -f "$file" ] && printf '%s  %s %s\n' "$(sha256sum <"$file" | cut -c1-64)" "$label" \
      "$(basename "$file")"
  done
}

run() {  # run LABEL MODEL.l [VIEW.v]
  local label=$1 model=$2 view=${3:-} stem env=()
  stem=${model%.l}
  [ -f "$stem.e" ] && env=(-e "$stem.e")
  local args=("$model")
  [ -n "$view" ] && args+=("$view")
  rm -rf "$work"/out && mkdir "$work"/out
  if "$hirsute" derive "${args[@]}" "${env[@]}" -o "$work/out/derived.str" >/dev/null 2>&1; then
    digest "$label derive" "$work/out/derived.str"
  else
    echo "exit $?  $label derive"
  fi
  if "$hirsute" export "${args[@]}" "${env[@]}" --pov "$work/out/scene.pov" \
    --obj "$work/out/scene.obj" --hairs "$work/out/hairs.csv" --feathers "$work/out/feathers.csv" \
    >/dev/null 2>&1; then
    digest "$label export" "$work"/out/scene* "$work/out/hairs.csv" "$work/out/feathers.csv"
  else
    echo "exit $?  $label export"
  fi
  if [ "$render" = 1 ]; then
    if "$hirsute" render "${args[@]}" "${env[@]}" -o "$work/out/image.png" --size 160x120 \
      >/dev/null 2>&1; then
      digest "$label render" "$work/out/image.png"
    else
      echo "exit $?  $label render"
    fi
  fi
}

cd "$root"
for folder in models/*/; do
  shopt -s nullglob
  lsystems=("$folder"*.l)
  views=("$folder"*.v)
  shopt -u nullglob
  for model in "${lsystems[@]}"; do
    stem=${model%.l}
    if [ -f "$stem.v" ]; then
      run "$model" "$model" "$stem.v"
    elif [ ${#views[@]} -eq 1 ]; then
      run "$model" "$model" "${views[0]}"
    else
      run "$model" "$model"
    fi
  done
  if [ ${#lsystems[@]} -eq 1 ]; then
    for view in "${views[@]}"; do
      [ -f "${view%.v}.l" ] || run "${lsystems[0]} $view" "${lsystems[0]}" "$view"
    done
  fi
done

conformance="$root/../shared/conformance"
if [ -d "$conformance" ]; then
  for folder in "$conformance"/*/; do
    for model in "$folder"*.l; do
      [ -f "$model" ] || continue
      stem=${model%.l}
      view=""
      [ -f "$stem.v" ] && view="$stem.v"
      run "conformance/$(basename "$folder")/$(basename "$model")" "$model" $view
    done
  done
fi
