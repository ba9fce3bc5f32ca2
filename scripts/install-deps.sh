#!/usr/bin/env bash
# Installs the Debian 12 packages Hirsute needs to build, test and benchmark.
# Idempotent: prints nothing and installs nothing when everything is present.
set -euo pipefail

packages=(
  build-essential cmake ninja-build cpp flex bison
  libcli11-dev libfmt-dev libxbyak-dev libgtest-dev libgmock-dev libbenchmark-dev libeigen3-dev libgmp-dev libnoise-dev
  clang libclang-rt-14-dev
  libglm-dev libosmesa6-dev libpng-dev libstb-dev povray zlib1g-dev pkg-config libembree-dev libopenexr-dev
  libassimp-dev libcgal-dev libboost-dev
  libglfw3-dev libimgui-dev xvfb xauth
  time parallel rsync ccache help2man man-db bash-completion
  blender python3-numpy
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

sudo=""
[ "$(id -u)" -ne 0 ] && sudo="sudo"
echo "Installing: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
