#!/usr/bin/env bash
# Builds here and packs what `obscura bench` needs on a GPU machine without packages:
#   gpu-pack.tar.xz  gpu-pack/: the harness, the plugin folder (plugInfo.json + library) and every
#              shared library they load (see pack-with-libs.sh), with gpu-pack/run to start them,
#              compressed (the libraries come to ~76 MB, ICU's data alone 30 MB, over what a device
#              call carries; bench/gpu-bench.sh unpacks it);
#   gpu-debs/  the Vulkan loader and the GL dispatch libraries the NVIDIA Vulkan driver needs.
# List both in .git/info/exclude and carry both to the device. Usage: bench/pack-for-gpu.sh PACK_TOOL
# (PACK_TOOL: the pack-with-libs.sh script of the workplace).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
pack_tool=${1:?usage: $0 path/to/pack-with-libs.sh}
# A build folder of its own, so the test build's settings stay as they are.
export OBSCURA_BUILD_DIR=$root/build-gpu
"$root/scripts/build.sh" -DOBSCURA_BUILD_TESTS=OFF -DCMAKE_BUILD_TYPE=Release >/dev/null
rm -rf "$root/gpu-pack" "$root/gpu-pack.tar.xz" "$root/gpu-debs"
"$pack_tool" "$root/gpu-pack" "$OBSCURA_BUILD_DIR/bin/obscura" \
  "$OBSCURA_BUILD_DIR/lib/obscura/plugin/obscura/libobscuraDelegate.so" "$OBSCURA_BUILD_DIR/lib/obscura/plugin/obscura"
mkdir -p "$root/gpu-debs"
(cd "$root/gpu-debs" && apt-get download libvulkan1 libglvnd0 libglx0 libegl1 libgl1 libopengl0 libgles2 >/dev/null)
tar -C "$root" -cJf "$root/gpu-pack.tar.xz" gpu-pack && rm -rf "$root/gpu-pack"
echo "packed gpu-pack.tar.xz and gpu-debs/"
