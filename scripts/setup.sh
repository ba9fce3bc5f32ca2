#!/usr/bin/env bash
# Installs what is missing, builds Hirsute (Release), and renders a shipped model to PNG.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)"

mkdir -p out
build/release/cli/hirsute render models/herb/herb.l models/herb/herb.v -o out/herb.png --size 800x800
echo "Rendered models/herb/herb.l into out/herb.png (the picture in the README was made this way)."
