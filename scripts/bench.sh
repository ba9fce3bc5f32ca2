#!/usr/bin/env bash
# Builds Hirsute in Release (without the tests) and prints the derivation benchmark's figures
# (in process, then the whole `hirsute derive` process timed with GNU time), then the
# interpretation benchmark's (string to Scene: modules and triangles per second), and with
# HAIRS=1 the hair benchmarks'.
# Arguments go to the derivation benchmark: --model NAME, --repeat N, --models DIR;
# INTERPRET_ARGS to the interpretation benchmark (e.g. "--model tubes --repeat 10").
#   scripts/bench.sh --repeat 5
# BUILD_DIR overrides the build folder; JOBS the build's parallel jobs (default: all cores).
set -euo pipefail
cd "$(dirname "$0")/.."

build="${BUILD_DIR:-build/bench}"
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DHIRSUTE_BUILD_TESTS=OFF \
  -DHIRSUTE_BUILD_BENCH=ON >/dev/null
cmake --build "$build" --target hirsute hirsute_derive_bench hirsute_interpret_bench \
  -j "${JOBS:-$(nproc)}"
"$build/bench/hirsute_derive_bench" "$@"
echo

# The same models as a user runs them: the whole `hirsute derive MODEL.l [MODEL.v] -o OUT`
# process (start-up, preprocessor, derivation, -str text), best wall time of RUNS (default 5)
# and the peak resident size that GNU time reports (the largest of hirsute and its cpp).
runs="${RUNS:-5}"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
printf '%-11s %12s %14s %12s\n' "model" "whole s" "peak MiB" "text bytes"
for model in models/bench/*.l; do
  name="$(basename "$model" .l)"
  [[ "$name" == tubes ]] && continue  # the interpretation benchmark's, not a derivation kind
  view=()
  [[ -f "${model%.l}.v" ]] && view=("${model%.l}.v")
  best=""
  peak=0
  for ((run = 0; run < runs; ++run)); do
    /usr/bin/time -f '%e %M' -o "$out/time" "$build/cli/hirsute" derive "$model" "${view[@]}" \
      -o "$out/$name.str"
    read -r seconds kib <"$out/time"
    if [[ -z "$best" ]] || awk -v a="$seconds" -v b="$best" 'BEGIN { exit !(a < b) }'; then
      best="$seconds"
    fi
    ((kib > peak)) && peak="$kib"
  done
  printf '%-11s %12s %14.1f %12s\n' "$name" "$best" "$(awk -v k="$peak" 'BEGIN { print k / 1024 }')" \
    "$(stat -c %s "$out/$name.str")"
done
echo "(whole process, best of $runs; peak resident size the largest of the runs, GNU time's %M)"
echo
# shellcheck disable=SC2086  # INTERPRET_ARGS is a list of arguments
"$build/bench/hirsute_interpret_bench" ${INTERPRET_ARGS:-}

# HAIRS=1 adds the hair benchmarks: the renderer's instanced hairs against raw GL lines of the
# same segments, and a million hairs exported (POV-Ray's parse time when povray is installed).
if [[ "${HAIRS:-0}" == 1 ]]; then
  cmake --build "$build" --target hirsute_hair_render_bench hirsute_hair_export_bench \
    -j "${JOBS:-$(nproc)}"
  echo
  "$build/bench/hirsute_hair_render_bench"
  echo
  "$build/bench/hirsute_hair_export_bench" --runs 1
fi
