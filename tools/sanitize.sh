#!/usr/bin/env bash
# The test suite under AddressSanitizer + UndefinedBehaviorSanitizer (gcc,
# build-asan/, tests only, benchmarks off; .ci/asan-exclude lists the few
# tests left out and why). Fails when a test fails or a sanitizer reports.
#   tools/sanitize.sh            (after tools/bootstrap.sh has installed what is needed)
set -euo pipefail
cd "$(dirname "$0")/.."

# -O1 and line tables only (-g1): sanitized code at -O2 took a third longer
# to compile, and this is CI's longest step. For the same reason the tests'
# own files are not instrumented (ROLLSENSE_TESTS_UNINSTRUMENTED): what they
# test, the libraries, plugins and programs, is. Reference results stay
# bit-identical at any -O level: the arithmetic is SSE2 with
# -ffp-contract=off (rollsense::sdk), never reassociated. A huge allocation
# is a report and a failure, never a machine out of memory.
sanitize="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
asan_build() {
  cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DROLLSENSE_BUILD_BENCH=OFF \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
    -DCMAKE_CXX_FLAGS="$sanitize" -DCMAKE_C_FLAGS="$sanitize" \
    -DCMAKE_EXE_LINKER_FLAGS="$sanitize" -DCMAKE_SHARED_LINKER_FLAGS="$sanitize" \
    -DCMAKE_MODULE_LINKER_FLAGS="$sanitize" -DROLLSENSE_TESTS_UNINSTRUMENTED=ON >/dev/null
  cmake --build build-asan -j"$(nproc 2>/dev/null || echo 2)"
}
asan_tests() {
  ASAN_OPTIONS=max_allocation_size_mb=3072:detect_stack_use_after_return=0:strict_string_checks=1 \
  UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --test-dir build-asan --output-on-failure -j2 -E "$(grep -v '^#' .ci/asan-exclude | paste -sd'|')"
}
asan_build
asan_tests

