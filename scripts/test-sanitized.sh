#!/usr/bin/env bash
# The same tests built with AddressSanitizer and UndefinedBehaviorSanitizer (Debug).
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
cmake --preset debug-asan >/dev/null
cmake --build --preset debug-asan -j "$(nproc)"
# Mesa's own blocks at exit are not ours to report (scripts/lsan.supp). LeakSanitizer's tracer,
# which scans every thread's memory at exit, crashed on a range of dynamic TLS recorded at a
# small bogus address (the GL libraries are loaded with dlopen; `render` of some models with some
# working folders, every time): intercept_tls_get_addr=0 keeps that record empty (static TLS is
# still scanned). Mesa starts no thread of its own either, so none can be ending while the tracer
# stops them: llvmpipe renders on the calling thread (LP_NUM_THREADS=0), no shader cache thread.
LP_NUM_THREADS=0 MESA_SHADER_CACHE_DISABLE=true \
  ASAN_OPTIONS=detect_leaks=1:intercept_tls_get_addr=0 UBSAN_OPTIONS=print_stacktrace=1 \
  LSAN_OPTIONS="suppressions=$PWD/scripts/lsan.supp:print_suppressions=0" \
  ctest --preset debug-asan -j "$(nproc)"
