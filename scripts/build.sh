#!/usr/bin/env bash
# Configures and builds into build/ (or $OBSCURA_BUILD_DIR) with extra CMake arguments passed on.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${OBSCURA_BUILD_DIR:-$root/build}
cmake -S "$root" -B "$build" -G Ninja "$@"
cmake --build "$build"
