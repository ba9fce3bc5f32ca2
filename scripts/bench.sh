#!/usr/bin/env bash
# Builds Hirsute in Release (without the tests) and prints the derivation benchmark's figures,
# then the interpretation benchmark's (string to Scene: modules and triangles per second), and with
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
cmake --build "$build" --target hirsute_derive_bench hirsute_interpret_bench -j "${JOBS:-$(nproc)}"
"$build/bench/hirsute_derive_bench" "$@"
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
