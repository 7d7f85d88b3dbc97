#!/usr/bin/env bash
# The test suite, but for its slowest tests (listed below), under AddressSanitizer + UndefinedBehaviorSanitizer
# (build-asan/): any memory error, leak or undefined behaviour fails the test that meets it.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build-sanitized.sh
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# Left out here: the tests labelled slow (cmake/testing.cmake; `ctest --test-dir build -N -L slow`
# lists them), which take minutes each under the sanitizers and run only in the Release pass. Each
# exercises code that a quicker test runs here too (their comments in tests/CMakeLists.txt say
# which): command-line runs of long scenes, scipy peers at tight tolerances, sweeps of many runs.
ctest --test-dir build-asan --output-on-failure -j "$(nproc)" -LE slow
