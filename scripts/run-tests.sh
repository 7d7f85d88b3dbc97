#!/usr/bin/env bash
# Sets up (bootstrap.sh) and runs the whole test suite with CTest.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/bootstrap.sh
ctest --test-dir build --output-on-failure -j "$(nproc)"
