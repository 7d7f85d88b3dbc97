#!/usr/bin/env bash
# clang-format and clang-tidy (.clang-format, .clang-tidy) on the C++ a change touches.
#   scripts/lint.sh [BASE]   the lines (format) and files (tidy) changed since BASE
#                            (default: HEAD~1, the last commit)
#   scripts/lint.sh --all    every source file (tidy only: the tree predates .clang-format)
# Installs clang-format and clang-tidy if missing and configures build-lint/ (clang, compile
# commands only, nothing built). Exit 1 on a finding.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-packages.sh clang clang-format clang-tidy
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
  # Only the changed lines must follow .clang-format: the files written before it stay as they are.
  format=$(git clang-format --diff --extensions cpp,hpp "$base" -- src apps python include tests 2>&1 || true)
  if ! grep -q 'no modified files\|did not modify' <<< "$format"; then
    echo "lint: lines changed since $base differ from .clang-format (git clang-format $base fixes them):"
    echo "$format"
    exit 1
  fi
fi
[ ${#files[@]} -eq 0 ] && { echo "lint: no C++ source changed"; exit 0; }
echo "lint: clang-tidy on ${#files[@]} files"
printf "%s\n" "${files[@]}" | xargs -P "$(nproc)" -n 1 clang-tidy -quiet -p build-lint 2>&1 | sed "/warnings generated\.$/d"
