#!/usr/bin/env bash
# clang-format on every C++ file of the tree (.clang-format: the tree was formatted once, the
# commit in .git-blame-ignore-revs, and stays so), and clang-tidy (.clang-tidy) on the sources a
# change touches.
#   scripts/lint.sh [BASE]   clang-tidy on the files changed since BASE (default: HEAD~1, the last commit)
#   scripts/lint.sh --all    clang-tidy on every source file
# Installs clang-format and clang-tidy if missing and configures build-lint/ (clang, compile
# commands only, nothing built). Exit 1 on a finding.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-packages.sh clang clang-format clang-tidy
mapfile -t unformatted < <(git ls-files '*.cpp' '*.hpp' '*.h' | xargs clang-format --dry-run --Werror 2>&1 |
                            sed -n 's/^\([^:]*\):[0-9]*:[0-9]*: error: code should be clang-formatted.*/\1/p' | sort -u)
if [ ${#unformatted[@]} -gt 0 ]; then
  echo "lint: ${#unformatted[@]} files differ from .clang-format (clang-format -i FILE fixes them):"
  printf "  %s\n" "${unformatted[@]}"
  exit 1
fi
cmake -S . -B build-lint -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_EXPORT_COMPILE_COMMANDS=ON > /dev/null
if [ "${1:-}" = "--all" ]; then
  mapfile -t files < <(git ls-files 'src/*.cpp' 'apps/*.cpp' 'python/*.cpp')
else
  base=${1:-HEAD~1}
  if ! git rev-parse -q --verify "$base^{commit}" > /dev/null; then
    echo "lint: no commit $base to compare with; nothing to check"
    exit 0
  fi
  mapfile -t files < <(git diff --name-only --diff-filter=d "$base" -- 'src/*.cpp' 'apps/*.cpp' 'python/*.cpp')
fi
[ ${#files[@]} -eq 0 ] && { echo "lint: no C++ source changed"; exit 0; }
echo "lint: clang-tidy on ${#files[@]} files"
printf "%s\n" "${files[@]}" | xargs -P "$(nproc)" -n 1 clang-tidy -quiet -p build-lint 2>&1 | sed "/warnings generated\.$/d"
