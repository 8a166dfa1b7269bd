#!/usr/bin/env bash
# Regression guard (not ground truth): the demo scene still renders as it did when the golden
# image was made. Correctness lives in the analytic tests; this catches unintended changes.
# Regenerate after an intended change with:
#   obscura render scenes/demo.usda -o tests/golden/demo_160x90.exr --width 160 --height 90 --aov color
set -eu
obscura=$1; src=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
OBSCURA_VALIDATION=1 "$obscura" render "$src/scenes/demo.usda" -o "$tmp/demo.exr" --width 160 --height 90 --aov color
"$obscura" compare "$tmp/demo.exr" "$src/tests/golden/demo_160x90.exr" --psnr-min 45 --ssim-min 0.99
