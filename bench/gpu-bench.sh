#!/usr/bin/env bash
# Runs on the GPU machine, from the repository root, after bench/pack-for-gpu.sh ran here:
# installs the carried Vulkan loader and GL dispatch libraries, then benchmarks each scene.
# Usage: [BENCH_ARGS="--msaa 4"] bench/gpu-bench.sh [FRAMES] [WIDTH] [HEIGHT] [SCENE...]
# BENCH_ARGS: more `obscura bench` options for every run (e.g. --msaa 4, --set key=value).
set -euo pipefail
frames=${1:-200}; width=${2:-1920}; height=${3:-1080}; shift $(( $# < 3 ? $# : 3 ))
read -r -a extra <<< "${BENCH_ARGS:-}"
scenes=("$@"); [ ${#scenes[@]} -gt 0 ] || scenes=(scenes/demo.usda)
[ -d gpu-pack ] || tar -xJf gpu-pack.tar.xz
for f in gpu-debs/*.deb; do dpkg -x "$f" /; done
ldconfig
export OBSCURA_PLUGINPATH=$PWD/gpu-pack/obscura
gpu-pack/run obscura info
for scene in "${scenes[@]}"; do
  gpu-pack/run obscura bench "$scene" --frames "$frames" --width "$width" --height "$height" "${extra[@]}"
  gpu-pack/run obscura bench "$scene" --frames "$frames" --width "$width" --height "$height" --json "${extra[@]}"
  # Temporal AA as under camera motion (reprojection, clamp) rather than settled into a still.
  gpu-pack/run obscura bench "$scene" --frames "$frames" --width "$width" --height "$height" --changing-camera "${extra[@]}"
done
