#!/usr/bin/env bash
# The same tests built with AddressSanitizer and UndefinedBehaviorSanitizer (Debug).
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
cmake --preset debug-asan >/dev/null
cmake --build --preset debug-asan -j "$(nproc)"
# Mesa's own blocks at exit are not ours to report (scripts/lsan.supp). Mesa starts no thread of
# its own: llvmpipe renders on the calling thread (LP_NUM_THREADS=0) and there is no shader cache
# and so no cache thread (MESA_SHADER_CACHE_DISABLE). LeakSanitizer's tracer, which stops every
# thread at exit, can crash when one of them is ending at that moment; this build tests our code.
LP_NUM_THREADS=0 MESA_SHADER_CACHE_DISABLE=true ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  LSAN_OPTIONS="suppressions=$PWD/scripts/lsan.supp:print_suppressions=0" \
  ctest --preset debug-asan -j "$(nproc)"
