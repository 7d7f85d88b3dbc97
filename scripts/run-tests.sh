#!/usr/bin/env bash
# Sets up (bootstrap.sh, and Chromium for the browser test) and runs the whole test suite with CTest; then, unless --quick,
# clang-format and clang-tidy on what the last commit changed (scripts/lint.sh), the same suite
# under AddressSanitizer + UndefinedBehaviorSanitizer (build-asan/) and a short smoke run of each
# fuzz target (FUZZ_SECONDS, default 20; scripts/fuzz.sh runs them for an hour).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-packages.sh chromium  # the report's browser test (tests/cli/test_animate_report.py)
./scripts/bootstrap.sh
ctest --test-dir build --output-on-failure -j "$(nproc)"
# The validation manifests' reports (pounding verify: junit.xml, verify.md), kept where CI keeps files.
for report in build/verify-*/; do
  [ -f "$report/junit.xml" ] || continue
  mkdir -p out/ci-reports/"$(basename "$report")"
  cp "$report"/junit.xml "$report"/verify.md out/ci-reports/"$(basename "$report")"/
done
[ "${1:-}" = "--quick" ] && exit 0
./scripts/lint.sh
./scripts/run-sanitized-tests.sh
./scripts/fuzz.sh "${FUZZ_SECONDS:-20}"
