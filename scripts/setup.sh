#!/usr/bin/env bash
# Installs the Debian 12 packages Obscura builds and runs with (scripts/debian-packages.txt), when any is missing.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
read -r -a packages <<< "$(sed 's/#.*//' "$root/scripts/debian-packages.txt" | tr '\n' ' ')"
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
