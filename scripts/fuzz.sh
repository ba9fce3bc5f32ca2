#!/usr/bin/env bash
# Builds the libFuzzer targets with the CMake preset `fuzz` (clang) and runs each for SECONDS:
# parse_derive_fuzzer (parser, compiler, derivation, homomorphism) and interpret_fuzzer (the same
# text interpreted into a Scene and covered with plant hairs).
#
#   scripts/fuzz.sh [SECONDS] [libFuzzer flags…]     (SECONDS defaults to 60, per target)
#   FUZZ_TARGETS=interpret_fuzzer scripts/fuzz.sh 600   (one target)
#
# The seed corpus is every `.l` under models/ and tests/ (and ../shared/conformance when it is
# there), each as written and as the C preprocessor hands it to the parser. Seeds, the growing
# corpus and any crash files live in build/fuzz/, never in the repository. A finding ends the run
# with a non-zero status and leaves its input in build/fuzz/artifacts/; replay it with
#   build/fuzz/fuzz/TARGET build/fuzz/artifacts/crash-…
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
seconds=${1:-60}
shift $(( $# > 0 ? 1 : 0 ))
build="$root/build/fuzz"

cd "$root"
cmake --preset fuzz >/dev/null
targets=(${FUZZ_TARGETS:-parse_derive_fuzzer interpret_fuzzer})
cmake --build --preset fuzz --target "${targets[@]}" -j "${JOBS:-1}"

seeds="$build/seeds"
corpus_root="$build/corpus"
artifacts="$build/artifacts"
rm -rf "$seeds"
mkdir -p "$seeds" "$artifacts"
folders=("$root/models" "$root/tests")
[ -d "$root/../shared/conformance" ] && folders+=("$root/../shared/conformance")
count=0
while IFS= read -r -d '' file; do
  name=$(printf '%s' "$file" | md5sum | cut -c1-16)
  cp "$file" "$seeds/$name.l"
  # What the parser sees in a real run: cpp's output with its line markers.
  cpp -traditional-cpp -undef -nostdinc -x c -I "$(dirname "$file")" "$file" \
    >"$seeds/$name.cpp.l" 2>/dev/null || rm -f "$seeds/$name.cpp.l"
  count=$((count + 1))
done < <(find "${folders[@]}" -name '*.l' -type f -print0 2>/dev/null)
echo "fuzz: $count seed files; running ${targets[*]} for $seconds s each" >&2

# libFuzzer's own work files go to the build folder too.
cd "$build"
for target in "${targets[@]}"; do
  corpus="$corpus_root/$target"
  mkdir -p "$corpus"
  echo "fuzz: $target" >&2
  "$build/fuzz/$target" \
    -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=8192 \
    -dict="$root/fuzz/lsystem.dict" -artifact_prefix="$artifacts/" -print_final_stats=1 \
    "$@" "$corpus" "$seeds"
done
