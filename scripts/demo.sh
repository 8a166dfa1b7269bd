#!/usr/bin/env bash
# Command 1 of the README: set up, build, render the bundled demo scene to out.png and out.exr.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
"$root/scripts/build.sh"
"$root/build/bin/obscura" render "$root/scenes/demo.usda" -o out.png --width 1280 --height 720
"$root/build/bin/obscura" render "$root/scenes/demo.usda" -o out.exr --width 1280 --height 720 \
  --aov color,depth,normal,albedo,primId
echo "wrote out.png and out.exr"
