#!/usr/bin/env bash
# Builds build-asan/: everything (library, program, tests, fuzz targets) with Debian's clang,
# AddressSanitizer and UndefinedBehaviorSanitizer (-O1 -g; toml++ compiled from its headers so
# it is instrumented too). Installs clang, its sanitizer runtimes and llvm-symbolizer (for
# readable reports) if missing. Usage: build-sanitized.sh [CMAKE --build ARGUMENTS...]
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-packages.sh clang libclang-rt-14-dev llvm-14
cmake -S . -B build-asan -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -gline-tables-only" \
  -DPOUNDING_SANITIZE=ON -DPOUNDING_BUILD_FUZZERS=ON -DPOUNDING_BUILD_BENCHMARKS=OFF > /dev/null
cmake --build build-asan -j "$(nproc)" "$@"
