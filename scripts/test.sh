#!/usr/bin/env bash
# Command 2 of the README (and CI): set up, build, run the whole suite on lavapipe with the
# Vulkan validation layer on. OBSCURA_SANITIZE=1 builds and tests with ASan + UBSan instead.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
"$root/scripts/setup.sh"
if [ "${OBSCURA_SANITIZE:-0}" = 1 ]; then
  export OBSCURA_BUILD_DIR=${OBSCURA_BUILD_DIR:-$root/build-sanitize}
  "$root/scripts/build.sh" -DOBSCURA_SANITIZE=ON -DCMAKE_BUILD_TYPE=Debug
  export LSAN_OPTIONS="suppressions=$root/tests/lsan.supp"
  export ASAN_OPTIONS="detect_leaks=1"
else
  export OBSCURA_BUILD_DIR=${OBSCURA_BUILD_DIR:-$root/build}
  "$root/scripts/build.sh"
fi
export OBSCURA_VALIDATION=1
ctest --test-dir "$OBSCURA_BUILD_DIR" --output-on-failure -j2 --timeout 600
