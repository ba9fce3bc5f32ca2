#!/usr/bin/env bash
# The feather-coat dynamics benchmark (docs/developers.md, "Feather-coat dynamics"): coats of
# about 64, 500 and 2 000 feathers on the bending body of models/coat-bending, in gusty wind, FRAMES frames at
# 24 frames a second while the body bends once, simulated with `hirsute simulate --no-frames`
# (the scenes are not written: the figures are the simulation's and the re-derived body's). Per
# coat: feathers and particles, the whole process's wall and CPU time and peak memory
# (/usr/bin/time -v), simulated frames a second, and per frame the steps, collision candidates,
# contacts and impact zones; then the steps retried, the intersections the final check found
# (in states thrown away), the pairs the impulses left between a quarter of the separation and the
# separation, the pairs with a calamus they left within the separation (calami are not
# guaranteed) and the pairs with a calamus found meeting their stem in a step tried (then
# retried as halves) and of those the ones put into impact zones at the smallest step, and the
# intersections left in accepted states (must be 0). The vane columns (docs/dynamics.md, "How the
# simulation works"):
# per frame the candidates and contacts with a vane's primitive, then the intersections of vanes
# with other vanes or stems in the frames' states, summed over the frames (0 with vanes on; with
# them off, what passed through, counted only with COUNT_VANES=1: the count costs as much as the
# steps of a coat without vanes; "-" otherwise).
# SIMULATED (default FRAMES) frames of them are simulated: fewer measure the start of the bend.
# VANES: "off" (the default), "on" (--vane-collisions) or both, one row each.
# RESTING: "on" (the default), "off" (--no-resting-contacts: the repulsion alone, as before the
# resting stage) or both, one row each. Its columns (docs/dynamics.md, "Resting contacts"): per
# step tried the resting contacts held, the searches for candidates and the pairs a search found,
# the CCD queries, and the contacts the net still caught (net/f), also as a share of the resting
# contacts (net%).
#   HIRSUTE=path/to/hirsute FRAMES=240 DENSITIES="4.9 38 152" VANES="off on" scripts/bench-dynamics.sh
set -euo pipefail
cd "$(dirname "$0")/.."
hirsute="$(realpath "${HIRSUTE:-build/release/cli/hirsute}")"
frames="${FRAMES:-240}"
simulated="${SIMULATED:-$frames}"
# KEEP=DIR keeps the runs (each coat's simulation.csv and summary) in DIR.
if [ -n "${KEEP:-}" ]; then
  work="$KEEP"
  mkdir -p "$work"
else
  work="$(mktemp -d)"
  trap 'rm -rf "$work"' EXIT
fi
printf '%-8s %5s %7s %9s %9s %6s %8s %8s %9s %10s %8s %11s %9s %7s %8s %11s %9s %11s %14s %11s %6s %12s %11s %10s %10s %8s %10s %10s %8s %7s\n' \
  density vanes resting feathers particles frames wall_s cpu_s peak_MiB frames/s steps/f candidates/f \
  contacts/f zones/f retried intersections kept_near calami_left calami_crossed calami_zoned left \
  vane_cand/f vane_cont/f vane_left resting/st searches/st pairs/search ccd/st net/st net%
for density in ${DENSITIES:-4.9 38 152}; do
for vanes in ${VANES:-off}; do
for resting in ${RESTING:-on}; do
  model="$work/coat-$density-$vanes-$resting"
  restingOption=""
  [ "$resting" = "off" ] && restingOption="--no-resting-contacts"
  vaneOption=""
  [ "$vanes" = "on" ] && vaneOption="--vane-collisions"
  [ "$vanes" = "off" ] && [ "${COUNT_VANES:-0}" = "1" ] && vaneOption="--count-vane-intersections"
  mkdir -p "$model"
  sed -e "s/^#define DENSITY .*/#define DENSITY $density/" \
      -e "s/^#define FRAMES .*/#define FRAMES $frames/" models/coat-bending/bending.l >"$model/bending.l"
  cp models/coat-bending/bending.v models/coat-bending/bending.a models/coat-bending/*.map \
    models/coat-bending/*.fea models/coat-bending/*.con "$model/"
  status=0
  (cd "$model" && /usr/bin/time -v "$hirsute" simulate bending.l bending.v bending.a -o out \
    --frames "$simulated" --no-frames -v --wind 0.5 0 0 --gusts 1 --gust-scale 2 $vaneOption $restingOption >summary.txt \
    2>time.txt) || status=$?
  if [ "$status" -ne 0 ]; then
    # A step that could not be resolved: the frames before it have their rows in the table.
    grep -m1 'error:' "$model/time.txt" >&2 || cat "$model/time.txt" >&2
    [ -f "$model/out/simulation.csv" ] || exit "$status"
    feathers="-"
    left="failed"
    vaneLeft="-"
  else
    # The counts behind the closing line, which -v prints on the standard error.
    summary="$(grep -E '^[0-9]+ frames of [0-9]+ feathers' "$model/time.txt")"
    feathers="$(sed -E 's/^[0-9]+ frames of ([0-9]+) feathers.*/\1/' <<<"$summary")"
    left="$(sed -E 's/.* ([0-9]+) left; vanes.*/\1/' <<<"$summary")"
    vaneLeft="-"
    grep -q ' vane intersections left$' <<<"$summary" &&
      vaneLeft="$(sed -E 's/.* ([0-9]+) vane intersections left$/\1/' <<<"$summary")"
  fi
  wall="$(awk -F': ' '/Elapsed \(wall clock\)/ {n = split($2, t, ":"); s = 0; for (i = 1; i <= n; i++) s = s * 60 + t[i]; print s}' "$model/time.txt")"
  cpu="$(awk -F': ' '/User time/ {u = $2} /System time/ {s = $2} END {print u + s}' "$model/time.txt")"
  peak="$(awk -F': ' '/Maximum resident/ {printf "%.0f", $2 / 1024}' "$model/time.txt")"
  awk -F, -v d="$density" -v v="$vanes" -v r="$resting" -v f="$feathers" -v wall="$wall" -v cpu="$cpu" -v peak="$peak" \
      -v left="$left" -v vaneLeft="$vaneLeft" -v segments=9 '
    NR > 2 {n++; steps += $4; candidates += $6; contacts += $7; zones += $10; retried += $5;
            found += $11; near += $12; calami += $13; crossed += $14; zoned += $15; seconds += $16;
            vaneCandidates += $17; vaneContacts += $18; tried += $4 + $5; resting += $21;
            searches += $22; searched += $23; ccd += $24; net += $25}
    END {printf "%-8s %5s %7s %9s %9s %6d %8.1f %8.1f %9s %10.1f %8.1f %11.0f %9.1f %7.2f %8d %11d %9d %11d %14d %11d %6s %12.0f %11.1f %10s %10.0f %8.1f %10.0f %10.0f %8.1f %7.2f\n",
         d, v, r, f, f == "-" ? "-" : f * segments, n + 1, wall, cpu, peak, n / seconds, steps / n, candidates / n,
         contacts / n, zones / n, retried, found, near, calami, crossed, zoned, left,
         vaneCandidates / n, vaneContacts / n, vaneLeft, resting / tried, searches / tried,
         (searches > 0 ? searched / searches : 0), ccd / tried, net / tried,
         (resting > 0 ? 100 * net / resting : 0)}' "$model/out/simulation.csv"
done
done
done
