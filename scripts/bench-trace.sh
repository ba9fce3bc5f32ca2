#!/usr/bin/env bash
# The path tracer against POV-Ray on the same view of the same model (issue 23's benchmark),
# all timed as whole processes with GNU time (wall seconds, peak MiB): `hirsute render --trace`
# at SPP samples a pixel; `hirsute export --pov` followed by POV-Ray 3.7 rendering the exported
# scene at the same size, once with the view's GL lights (+A0.3 antialiasing) and once with the
# tracer's own lights (`--trace-lights`: an area light and the sky by radiosity, the same set-up
# as the tracer's). The tracer's noise is the RMS difference, in 8-bit display levels, between
# its picture and one of another seed, over sqrt(2) (scripts/image-noise.py). Prints one row a
# model; the speed columns are POV-Ray's export and render time over the tracer's.
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

printf '%-16s %15s %6s %15s %15s %8s %15s %15s %8s\n' "model" "trace s/MiB" "noise" \
  "export s/MiB" "POV GL s/MiB" "speed" "export s/MiB" "POV trace s/MiB" "speed"
for m in $models; do
  folder="$root/models/$(dirname "$m")"
  base="$(basename "$m")"
  read -r ts tm < <(timed "$program" render "$folder/$base.l" "$folder/$base.v" --trace \
    --spp "$spp" --size "$size" -o "$work/$base-trace.png")
  "$program" render "$folder/$base.l" "$folder/$base.v" --trace --spp "$spp" --size "$size" \
    --seed 2 -o "$work/$base-trace2.png" 2> /dev/null
  noise="$(python3 "$root/scripts/image-noise.py" "$work/$base-trace.png" "$work/$base-trace2.png")"
  row="$(printf '%-16s %15s %6s' "$base" "$ts/$tm" "$noise")"
  for lights in "" "--trace-lights"; do
    read -r es em < <(timed "$program" export "$folder/$base.l" "$folder/$base.v" $lights \
      --pov "$work/$base.pov" --width "${size%x*}" --height "${size#*x}")
    read -r ps pm < <(timed timeout "${POVRAY_LIMIT:-1800}" povray -D +A0.3 +W"${size%x*}" \
      +H"${size#*x}" +I"$work/$base.pov" +O"$work/$base-pov.png")
    ratio="$(awk -v t="$ts" -v e="$es" -v p="$ps" 'BEGIN { if (p == "failed") print "-"; else printf "%.1fx", (e + p) / t }')"
    row+="$(printf ' %15s %15s %8s' "$es/$em" "$ps/$pm" "$ratio")"
  done
  echo "$row"
done
