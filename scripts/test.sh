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
  # intercept_tls_get_addr=0: up to GCC 13 the runtime's __tls_get_addr interceptor mistakes a
  # dynamic TLS block that happens to start 16 bytes into a page for a pre-2.25 glibc header and
  # hands LeakSanitizer a range that crashes its tracer at exit (google/sanitizers#1322). Blocks
  # held only from dynamically loaded libraries' thread-locals would then read as leaks; none does.
  export ASAN_OPTIONS="detect_leaks=1:intercept_tls_get_addr=0"
else
  export OBSCURA_BUILD_DIR=${OBSCURA_BUILD_DIR:-$root/build}
  "$root/scripts/build.sh"
fi
export OBSCURA_VALIDATION=1
ctest --test-dir "$OBSCURA_BUILD_DIR" --output-on-failure -j2 --timeout 600
