#!/usr/bin/env bash
# Dense feather coats drawn and exported (issue 26, item 4): models/bench/feather-coat.l with its
# DENSITY set for about 1 000, 10 000 and 30 000 feathers, each measured as the user meets it,
# the whole process under GNU time (wall seconds, peak MiB):
#   render   `hirsute render MODEL -o coat.png --size 800x600`
#   export   `hirsute export MODEL --pov coat.pov --size 640x480` (its size in MiB)
#   povray   `povray +W640 +H480 -D +FN coat.pov`, stopped after POV_TIMEOUT seconds (default 120):
#            "not finished in N s"
# and the templates the export declared for its feathers (`#declare Feather`).
#   scripts/bench-coat.sh                  (builds build/release first)
# HIRSUTE=PATH skips the build; BEFORE=PATH measures another build beside it (e.g. the commit
# before), row for row; DENSITIES="80.5 805" picks the coats; RUNS (default 1) takes the best.
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
before="${BEFORE:+$(realpath "$BEFORE")}"
densities="${DENSITIES:-80.5 805 2415}"
pov_timeout="${POV_TIMEOUT:-120}"
runs="${RUNS:-1}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cp "$root/models/bench/"{feather-coat.v,strip.con,brown.fea,grey.fea,green.fea,blue.fea} "$work/"
cd "$work"

# Runs "$@" RUNS times under GNU time; prints "seconds MiB" of the fastest run, or
# "exit CODE" when it failed.
timed() {
  local best="" best_kib=0 status=0
  for ((r = 0; r < runs; ++r)); do
    status=0
    /usr/bin/time -f "%e %M" -o time.txt "$@" > out.txt 2> err.txt || status=$?
    if [[ $status -ne 0 ]]; then
      echo "exit $status"
      return
    fi
    read -r seconds kib < <(tail -1 time.txt)
    if [[ -z "$best" ]] || awk "BEGIN { exit !($seconds < $best) }"; then
      best="$seconds"
      best_kib="$kib"
    fi
  done
  printf '%s %d\n' "$best" "$((best_kib / 1024))"
}

printf '%-8s %-7s %8s | %8s %8s | %8s %8s %8s %9s | %-22s\n' "density" "build" "feathers" \
  "render s" "MiB" "export s" "MiB" "pov MiB" "templates" "povray 640x480 s, MiB"
for density in $densities; do
  sed "s/^#define DENSITY .*/#define DENSITY $density/" "$root/models/bench/feather-coat.l" \
    > "coat-$density.l"
  for build in after before; do
    hirsute="$program"
    if [[ $build == before ]]; then
      [[ -n "$before" ]] || continue
      hirsute="$before"
    fi
    feathers="$("$hirsute" export "coat-$density.l" feather-coat.v --feathers f.csv > /dev/null 2>&1 &&
      tail -n +2 f.csv | wc -l || echo '?')"
    render="$(timed "$hirsute" render "coat-$density.l" feather-coat.v -o coat.png --size 800x600)"
    exported="$(timed "$hirsute" export "coat-$density.l" feather-coat.v --pov coat.pov \
      --size 640x480)"
    pov_mib="-" templates="-" povray="-"
    if [[ -f coat.pov && $exported != exit* ]]; then
      pov_mib="$(awk "BEGIN { printf \"%.1f\", $(stat -c %s coat.pov) / 1048576 }")"
      templates="$(grep -c '^#declare Feather' coat.pov || true)"
      status=0
      /usr/bin/time -f "%e %M" -o time.txt timeout "$pov_timeout" \
        povray +Icoat.pov +Ocoat-pov.png +W640 +H480 -D +FN > /dev/null 2> pov-err.txt ||
        status=$?
      if [[ $status -eq 124 ]]; then
        povray="not finished in $pov_timeout s"
      elif [[ $status -ne 0 ]]; then
        povray="exit $status"
      else
        read -r seconds kib < <(tail -1 time.txt)
        povray="$seconds $((kib / 1024))"
      fi
    fi
    rm -f coat.pov coat.png coat-pov.png
    read -r render_s render_mib <<< "$render"
    read -r export_s export_mib <<< "$exported"
    printf '%-8s %-7s %8s | %8s %8s | %8s %8s %8s %9s | %-22s\n' "$density" "$build" "$feathers" \
      "$render_s" "$render_mib" "$export_s" "$export_mib" "$pov_mib" "$templates" "$povray"
  done
done
