#!/usr/bin/env bash
# Builds Hirsute (Release) and runs every test: unit tests, the broken-input corpus, and the
# conformance runner over ../shared/conformance, vlab's models with cpfg's own strings (skipped
# when that folder is absent; docs/design.md, "Tests and CI").
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)"
ctest --preset release -j "$(nproc)"
build/release/tests/hirsute_conformance ../shared/conformance || [ $? -eq 77 ]
