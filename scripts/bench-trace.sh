#!/usr/bin/env bash
# The path tracer against POV-Ray on the same view of the same model (issue 23's benchmark),
# all timed as whole processes with GNU time (wall seconds, peak MiB): `hirsute render --trace`
# at each of SETTINGS; `hirsute export --pov` followed by POV-Ray 3.7 rendering the exported
# scene at the same size, once with the view's GL lights (+A0.3 antialiasing) and once with the
# tracer's own lights (`--trace-lights`: an area light and the sky by radiosity, the same set-up
# as the tracer's). The tracer's noise is the RMS difference, in 8-bit display levels, between
# its picture and one of another seed, over sqrt(2), over the whole plant and in its noisiest
# 8x8 tiles (the 99th percentile; scripts/image-noise.py --tiles). Prints one row a
# model; the speed columns are POV-Ray's export and render time over the tracer's.
#   scripts/bench-trace.sh                 (builds build/release first)
# HIRSUTE=PATH skips the build; SIZE (default 800x600), SETTINGS (default "64:0": one or more
# SPP:NOISE or SPP:NOISE:dn, the --spp and --noise of a tracer's run, and with ":dn" --denoise,
# each its own row, run one after another for each model, so that uniform and adaptive sampling
# are timed side by side; a denoised picture's noise between seeds leaves out what the filter
# blurs: scripts/image-noise.py --reference measures that against a reference) and MODELS
# (default "nankin-cherry/nankin-cherry oriental-poppy/oriental-poppy wild-crocus/wild-crocus",
# each a models/ folder and the base name of its .l and .v) choose what is run; POVRAY=0 leaves
# POV-Ray out; POVRAY_LIMIT (seconds, default 1800) stops a POV-Ray run that takes longer,
# reported as failed. A row's "spp" is the mean samples a pixel the tracer took. KEEP=DIR keeps
# the tracer's pictures and sample counts there (MODEL-SPP-NOISE.png, ...-spp.png).
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
settings="${SETTINGS:-64:0}"
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

printf '%-16s %9s %7s %15s %12s %15s %15s %8s %15s %15s %8s\n' "model" "spp:noise" "spp" \
  "trace s/MiB" "noise/tiles" "export s/MiB" "POV GL s/MiB" "speed" "export s/MiB" "POV trace s/MiB" "speed"
for m in $models; do
  folder="$root/models/$(dirname "$m")"
  base="$(basename "$m")"
  pov=""
  for setting in $settings; do
    IFS=: read -r spp noise denoise <<<"$setting"
    trace=("$program" render "$folder/$base.l" "$folder/$base.v" --trace --spp "$spp" --noise
      "$noise" --size "$size" -v)
    [[ "$denoise" == dn ]] && trace+=(--denoise)
    read -r ts tm < <(timed "${trace[@]}" -o "$work/$base-trace.png" --spp-image "$work/$base-spp.png")
    mean="$(sed -n 's/^traced \([0-9.]*\) samples a pixel on average.*/\1/p' "$work/err.txt")"
    "${trace[@]}" --seed 2 -o "$work/$base-trace2.png" 2> /dev/null
    measured="$(python3 "$root/scripts/image-noise.py" --tiles "$work/$base-trace.png" "$work/$base-trace2.png")"
    row="$(printf '%-16s %9s %7s %15s %12s' "$base" "$setting" "$mean" "$ts/$tm" "${measured/ //}")"
    if [[ -n "${KEEP:-}" ]]; then
      mkdir -p "$KEEP"
      cp "$work/$base-trace.png" "$KEEP/$base-$spp-$noise${denoise:+-$denoise}.png"
      cp "$work/$base-spp.png" "$KEEP/$base-$spp-$noise-spp.png"
    fi
    if [[ "${POVRAY:-1}" != 0 && -z "$pov" ]]; then
      for lights in "" "--trace-lights"; do
        read -r es em < <(timed "$program" export "$folder/$base.l" "$folder/$base.v" $lights \
          --pov "$work/$base.pov" --size "$size")
        read -r ps pm < <(timed timeout "${POVRAY_LIMIT:-1800}" povray -D +A0.3 +W"${size%x*}" \
          +H"${size#*x}" +I"$work/$base.pov" +O"$work/$base-pov.png")
        pov+="$(printf ' %15s %15s' "$es/$em" "$ps/$pm") $es $ps "
      done
    fi
    # POV-Ray's columns: measured once a model, the speed against each of the tracer's rows.
    set -- $pov
    while (( $# >= 4 )); do
      ratio="$(awk -v t="$ts" -v e="$3" -v p="$4" 'BEGIN { if (p == "failed") print "-"; else printf "%.1fx", (e + p) / t }')"
      row+="$(printf ' %15s %15s %8s' "$1" "$2" "$ratio")"
      shift 4
    done
    echo "$row"
  done
done
