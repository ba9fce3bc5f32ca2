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
# no .l is named after is run with the folder's only .l. X.e beside it is its environment. The
# conformance models run as their index.tsv gives them (.l, .v, colour file, steps).
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

run() {  # run LABEL MODEL.l [VIEW.v [OPTION…]]
  local label=$1 model=$2 view=${3:-} stem env=()
  shift 3 2>/dev/null || shift $#
  stem=${model%.l}
  [ -f "$stem.e" ] && env=(-e "$stem.e")
  local args=("$model")
  [ -n "$view" ] && args+=("$view")
  args+=("$@")
  # derive takes no colour or material file.
  local derive=() i
  for ((i = 0; i < ${#args[@]}; i++)); do
    case ${args[i]} in -m* | -M*) i=$((i + 1)) ;; *) derive+=("${args[i]}") ;; esac
  done
  rm -rf "$work"/out && mkdir "$work"/out
  if "$hirsute" derive "${derive[@]}" "${env[@]}" -o "$work/out/derived.str" >/dev/null 2>&1; then
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
if [ -f "$conformance/index.tsv" ]; then
  # Each model as its index gives it: its .l and .v, its colour or material file, its steps.
  tail -n +2 "$conformance/index.tsv" |
    while IFS=$'\t' read -r id lfile vfile afile colors steps environment rest; do
      folder="$conformance/$id"
      [ -f "$folder/$lfile" ] || continue
      view=""
      [ "$vfile" != "-" ] && view="$folder/$vfile"
      options=(-n "$steps")
      # "-M material.mat", "-m1 sedge.map -m2 sedge.map2": options, each with a name in the folder.
      if [ "$colors" != "-" ]; then
        read -r -a more <<<"$colors"
        for ((k = 0; k + 1 < ${#more[@]}; k += 2)); do
          option=${more[k]} bank=${more[k]:2}
          if [ -n "$bank" ]; then  # cpfg's -m2 FILE is -m 2:FILE here
            options+=("${option:0:2}" "$bank:$folder/${more[k + 1]}")
          else
            options+=("$option" "$folder/${more[k + 1]}")
          fi
        done
      fi
      run "conformance/$id/$lfile" "$folder/$lfile" "$view" "${options[@]}"
    done
fi
