#!/usr/bin/env bash
# Our path tracer against Blender's Cycles on the same view of the same model, at equal noise,
# as whole processes under GNU time (`/usr/bin/time -v`: wall seconds and peak resident memory):
#   - Cycles: `hirsute export --blender`, then headless Blender 3.4 importing the scene with the
#     add-on blender/hirsute_import.py (hairs as Curves of their radius with the principled hair
#     BSDF, surfaces with the principled BSDF, the view file's camera) and rendering it in Cycles
#     on the CPU at SAMPLES samples a pixel (uniform sampling, no denoising), lit as the tracer
#     is: a sun of the view's `trace light:` and a sky of its
#     `trace sky:` (scripts/bench-cycles-scene.py);
#   - the tracer: `hirsute render --trace` at the same size, uniform sampling (--noise 0) with
#     the samples a pixel that give Cycles' noise: a first run at PROBE samples measures the
#     tracer's noise, which falls as 1/sqrt(samples), and the timed run takes
#     PROBE * (its noise / Cycles' noise)^2 samples; its noise is measured again.
# Noise: scripts/image-noise.py, the RMS difference in 8-bit display levels between the picture
# and one of another seed, over sqrt(2), over the plant (not the background). What differs
# still: the tracer's translucent leaves, veins and hair model (docs/trace.md) are its own.
#
#   scripts/bench-cycles.sh            (builds build/release first)
#
# HIRSUTE=PATH skips the build; MODEL (default nankin-cherry/nankin-cherry), VIEW (default
# closeup.v in the model's folder), SIZE (default 320x240), SAMPLES (default 64), PROBE (default
# 16) and BLENDER (default blender) choose what is run; KEEP=DIR keeps the four pictures.
set -euo pipefail
cd "$(dirname "$0")/.."
root="$PWD"
program="${HIRSUTE:-}"
if [[ -z "$program" ]]; then
  cmake --preset release >/dev/null
  cmake --build --preset release --target hirsute hirsute_drawing hirsute_tracing >/dev/null
  program="$root/build/release/cli/hirsute"
fi
program="$(realpath "$program")"
blender="${BLENDER:-blender}"
command -v "$blender" >/dev/null || { echo "bench-cycles: $blender is not installed" >&2; exit 1; }
model="${MODEL:-nankin-cherry/nankin-cherry}"
folder="$root/models/$(dirname "$model")"
lsystem="$folder/$(basename "$model").l"
view="$folder/${VIEW:-closeup.v}"
size="${SIZE:-320x240}"
samples="${SAMPLES:-64}"
probe="${PROBE:-16}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

timed() {  # runs the command under GNU time -v; prints "seconds MiB", or fails with its errors
  if ! /usr/bin/time -v -o "$work/time.txt" "$@" > "$work/out.txt" 2> "$work/err.txt"; then
    tail -5 "$work/err.txt" >&2
    return 1
  fi
  awk -F': ' '/Elapsed \(wall clock\)/ { n = split($2, t, ":"); s = 0
                                          for (i = 1; i <= n; ++i) s = s * 60 + t[i] }
              /Maximum resident set size/ { kib = $2 }
              END { printf "%.2f %d\n", s, kib / 1024 }' "$work/time.txt"
}
noise() { python3 "$root/scripts/image-noise.py" "$1" "$2"; }
# The view's `trace light:` and `trace sky:` (the view file and the files it includes; the last
# line of each counts).
view_text="$(cat "$view" $(sed -n 's/^#include "\(.*\)"/\1/p' "$view" | sed "s|^|$(dirname "$view")/|"))"
light="$(sed -n 's/^trace light: *D: *\([^ ]*\) *A: *\([^ ]*\) *I: *\([^ ]*\).*/\1 \2 \3/p' <<<"$view_text" | tail -1)"
sky="$(sed -n 's/^trace sky: *\([^ ]*\).*/\1/p' <<<"$view_text" | tail -1)"
if [[ -z "$light" || -z "$sky" ]]; then
  echo "bench-cycles: $view has no 'trace light: D: … A: … I: …' or 'trace sky:' line" >&2
  exit 1
fi

# The commands, with what is added: Cycles' run ("${cycles[@]}" OUT.png SEED "$light" "$sky"),
# and the tracer's ("${trace[@]}" SPP --seed SEED -o OUT.png).
cycles=("$blender" -b --factory-startup --python-exit-code 1 --python
  "$root/scripts/bench-cycles-scene.py" -- "$work/scene.hirsute" "$samples")
trace=("$program" render "$lsystem" "$view" --trace --noise 0 --size "$size" --spp)

echo "$(basename "$model") ($(basename "$view")) at $size on $(nproc) cores, $(date -u '+%F %H:%M UTC')"
# Cycles: the export, then Blender's import and render, each a process of its own.
read -r es em < <(timed "$program" export "$lsystem" "$view" --blender "$work/scene.hirsute" \
  --size "$size")
[[ -n "${es:-}" ]] || exit 1
read -r cs cm < <(timed "${cycles[@]}" "$work/cycles.png" 0 "$light" "$sky")
[[ -n "${cs:-}" ]] || exit 1
# Of which Cycles' render itself (Blender's "Time: MM:SS.ss"), from synchronising the scene on.
rendering="$(sed -n 's/^ *Time: \([0-9:.]*\) (Saving.*/\1/p' "$work/out.txt" | tail -1 |
  awk -F: '{ s = 0; for (i = 1; i <= NF; ++i) s = s * 60 + $i; printf "%.2f", s }')"
"${cycles[@]}" "$work/cycles-2.png" 1 "$light" "$sky" > /dev/null 2>&1
cycles_noise="$(noise "$work/cycles.png" "$work/cycles-2.png")"

# The tracer: its noise at PROBE samples, then the samples for Cycles' noise.
"${trace[@]}" "$probe" --seed 1 -o "$work/probe.png" 2> /dev/null
"${trace[@]}" "$probe" --seed 2 -o "$work/probe-2.png" 2> /dev/null
probe_noise="$(noise "$work/probe.png" "$work/probe-2.png")"
spp="$(awk -v p="$probe" -v t="$probe_noise" -v c="$cycles_noise" \
  'BEGIN { s = p * (t / c) ^ 2; s = int(s + 0.999); print (s < 1 ? 1 : s) }')"
read -r ts tm < <(timed "${trace[@]}" "$spp" --seed 1 -o "$work/trace.png")
[[ -n "${ts:-}" ]] || exit 1
"${trace[@]}" "$spp" --seed 2 -o "$work/trace-2.png" 2> /dev/null
trace_noise="$(noise "$work/trace.png" "$work/trace-2.png")"

printf '%-44s %10s %9s %6s\n' "process" "wall s" "peak MiB" "noise"
printf '%-44s %10s %9s %6s\n' "hirsute export --blender" "$es" "$em" ""
printf '%-44s %10s %9s %6s\n' "blender: import + Cycles, $samples samples" "$cs" "$cm" \
  "$cycles_noise"
printf '%-44s %10s\n' "  of which Cycles' render" "$rendering"
printf '%-44s %10s %9s %6s\n' "Cycles in all (export + Blender)" \
  "$(awk -v a="$es" -v b="$cs" 'BEGIN { printf "%.2f", a + b }')" \
  "$(( em > cm ? em : cm ))" "$cycles_noise"
printf '%-44s %10s %9s %6s\n' "hirsute render --trace, $spp samples (uniform)" "$ts" "$tm" \
  "$trace_noise"
awk -v a="$es" -v b="$cs" -v t="$ts" 'BEGIN { printf "the tracer is %.1fx as fast as Cycles\n", (a + b) / t }'
if [[ -n "${KEEP:-}" ]]; then
  mkdir -p "$KEEP"
  cp "$work/cycles.png" "$work/cycles-2.png" "$work/trace.png" "$work/trace-2.png" "$KEEP/"
fi
