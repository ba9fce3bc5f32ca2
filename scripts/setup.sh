#!/usr/bin/env bash
# Installs what is missing, builds Hirsute (Release), and runs the main job on a shipped model.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)"

mkdir -p out
build/release/cli/hirsute derive models/herb/herb.l models/herb/herb.v -o out/herb.str
echo "Derived models/herb/herb.l into out/herb.str ($(wc -c < out/herb.str) bytes):"
head -c 400 out/herb.str
echo "…"
