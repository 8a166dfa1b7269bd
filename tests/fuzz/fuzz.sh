#!/usr/bin/env bash
# The suite's fuzzing (tests/CMakeLists.txt):
#   fuzz.sh build SOURCE_DIR FUZZ_BUILD_DIR   configure a clang build tree with -DOBSCURA_FUZZ=ON and build the targets
#   fuzz.sh run FUZZER CORPUS_DIR SECONDS [TIMEOUT]   run one target over a copy of the committed
#                                             corpus; an input slower than TIMEOUT s (10) is a finding
# A crash, leak, sanitizer report or timeout makes libFuzzer exit non-zero; the reproducer is
# left in the working directory (crash-*, leak-*, timeout-*).
set -euo pipefail
case "$1" in
build)
    src=$2 build=$3
    launcher=()
    command -v ccache >/dev/null && launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
    cmake -S "$src" -B "$build" -G Ninja -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
        -DOBSCURA_FUZZ=ON -DOBSCURA_BUILD_TESTS=OFF "${launcher[@]}" >/dev/null
    cmake --build "$build" --target obscura_fuzzers
    ;;
run)
    fuzzer=$2 corpus=$3 seconds=$4 timeout=${5:-10}
    work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
    cp -r "$corpus/." "$work/"
    # The suite's suppressions (Vulkan driver, validation layer, LLVM: tests/lsan.supp) and the fuzz
    # targets' own (a third-party importer).
    here=$(cd "$(dirname "$0")" && pwd)
    cat "$here/../lsan.supp" "$here/lsan.supp" >"$work.supp"
    trap 'rm -rf "$work" "$work.supp"' EXIT
    export LSAN_OPTIONS="suppressions=$work.supp"
    # Inputs grow to a few scene files' size; a slow input or one above 2 GB is a finding.
    "$fuzzer" -max_total_time="$seconds" -max_len=16384 -timeout="$timeout" -rss_limit_mb=2048 -print_final_stats=1 "$work"
    ;;
*)
    echo "usage: fuzz.sh build SOURCE_DIR BUILD_DIR | run FUZZER CORPUS_DIR SECONDS [TIMEOUT]" >&2
    exit 2
    ;;
esac
