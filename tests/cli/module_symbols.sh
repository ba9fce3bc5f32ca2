#!/usr/bin/env bash
# The modules the program loads when first needed (libhirsute-drawing.so, libhirsute-trace.so,
# …: core/loadable_module.h) link everything of Hirsute they use: a symbol of Hirsute's left
# undefined in one is found by nothing at dlopen, and the command fails only when it runs. The
# organ registries declare their organs' entry points themselves (hairs/organs/organ_list.h), so
# a declaration that does not match its definition shows up here, at build time, and not as
# `render --trace` failing.
#
#   module_symbols.sh MODULE…
set -euo pipefail
status=0
for module in "$@"; do
  undefined=$(nm -D --undefined-only "$module" | c++filt | grep -E ' hirsute::' || true)
  if [ -n "$undefined" ]; then
    echo "$module leaves Hirsute's symbols undefined:" >&2
    echo "$undefined" >&2
    status=1
  fi
done
exit $status
