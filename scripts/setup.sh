#!/usr/bin/env bash
# Installs what is missing, builds Hirsute (Release), installs it (`hirsute` in /usr/local/bin,
# its modules in /usr/local/lib/hirsute, `man hirsute`, bash completion) and renders two shipped
# models to PNG: a hairy plant (the oriental poppy, 120 000 hairs) and the herb.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release -j "$(nproc)"
sudo=""
[ "$(id -u)" -ne 0 ] && sudo="sudo"
$sudo cmake --install build/release >/dev/null
hirsute=$(command -v hirsute || echo /usr/local/bin/hirsute)
echo "Installed $hirsute (man hirsute; bash completes its commands and options)."

mkdir -p out
"$hirsute" render models/oriental-poppy/oriental-poppy.l models/oriental-poppy/oriental-poppy.v \
  -o out/oriental-poppy.png --size 800x600 -v
"$hirsute" render models/herb/herb.l models/herb/herb.v -o out/herb.png --size 800x800
echo "Rendered models/oriental-poppy into out/oriental-poppy.png and models/herb into out/herb.png"
echo "(the README's first two pictures were made this way)."
