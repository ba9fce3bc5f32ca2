#!/usr/bin/env bash
# Installs what is missing, builds Hirsute (Release), and renders two shipped models to PNG: a
# hairy plant (the oriental poppy, 120 000 hairs) and the herb.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)"

mkdir -p out
build/release/cli/hirsute render models/oriental-poppy/oriental-poppy.l \
  models/oriental-poppy/oriental-poppy.v -o out/oriental-poppy.png --size 800x600 -v
build/release/cli/hirsute render models/herb/herb.l models/herb/herb.v -o out/herb.png --size 800x800
echo "Rendered models/oriental-poppy into out/oriental-poppy.png and models/herb into out/herb.png"
echo "(the README's first two pictures were made this way)."
