#!/usr/bin/env bash
# The path tracer against POV-Ray on the same view of the same model (issue 23's benchmark),
# both timed as whole processes with GNU time (wall seconds, peak MiB): `hirsute render --trace`
# at SPP samples a pixel, and `hirsute export --pov` followed by POV-Ray 3.7 rendering the
# exported scene at the same size. Prints one row a model.
#   scripts/bench-trace.sh                 (builds build/release first)
# HIRSUTE=PATH skips the build; SIZE (default 800x600), SPP (default 64) and MODELS (default
# "nankin-cherry/nankin-cherry oriental-poppy/oriental-poppy wild-crocus/wild-crocus", each a
# models/ folder and the base name of its .l and .v) choose what is run; POVRAY_LIMIT (seconds,
# default 1800) stops a POV-Ray run that takes longer, reported as failed.
set -euo pipefail
cd "$(dirname "$0")/.."
root="$PWD"
program="${HIRSUTE:-}"
if [[ -z "$program" ]]; then
  cmake --preset release >/dev/null
  cmake --build --preset release --target hirsute hirsute_drawing >/dev/null
  program="$root/build/release/cli/hirsute"
fi
program="$(realpath "$program")"
size="${SIZE:-800x600}"
spp="${SPP:-64}"
models="${MODELS:-nankin-cherry/nankin-cherry oriental-poppy/oriental-poppy wild-crocus/wild-crocus}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

timed() {  # prints "seconds MiB" of the command, or "failed"
  if /usr/bin/time -f "%e %M" -o "$work/time.txt" "$@" > "$work/out.txt" 2> "$work/err.txt"; then
    read -r seconds kib < "$work/time.txt"
    echo "$seconds $((kib / 1024))"
  else
    echo "failed"
    tail -3 "$work/err.txt" >&2
  fi
}

printf '%-16s %22s %22s %22s %8s\n' "model" "trace s / MiB" "export s / MiB" "POV-Ray s / MiB" "speed"
for m in $models; do
  folder="$root/models/$(dirname "$m")"
  base="$(basename "$m")"
  read -r ts tm < <(timed "$program" render "$folder/$base.l" "$folder/$base.v" --trace \
    --spp "$spp" --size "$size" -o "$work/$base-trace.png")
  read -r es em < <(timed "$program" export "$folder/$base.l" "$folder/$base.v" \
    --pov "$work/$base.pov" --width "${size%x*}" --height "${size#*x}")
  read -r ps pm < <(timed timeout "${POVRAY_LIMIT:-1800}" povray -D +A0.3 +W"${size%x*}" +H"${size#*x}" +I"$work/$base.pov" \
    +O"$work/$base-pov.png")
  ratio="$(awk -v t="$ts" -v e="$es" -v p="$ps" 'BEGIN { printf "%.1fx", (e + p) / t }')"
  printf '%-16s %22s %22s %22s %8s\n' "$base" "$ts / $tm" "$es / $em" "$ps / $pm" "$ratio"
done
