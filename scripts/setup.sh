#!/usr/bin/env bash
# Installs the Debian 12 packages Obscura builds and runs with, when any is missing.
set -euo pipefail
packages=(
  cmake ninja-build g++ pkg-config python3
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools
  glslang-dev glslang-tools spirv-tools
  libopenexr-dev openexr libimath-dev libpng-dev libstb-dev libopencolorio-dev
  nlohmann-json3-dev libcli11-dev libgtest-dev libbenchmark-dev libosd-dev libassimp-dev
  clang libclang-rt-14-dev
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}"
  sudo_cmd=()
  [ "$(id -u)" -ne 0 ] && sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
