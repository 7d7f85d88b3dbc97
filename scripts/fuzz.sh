#!/usr/bin/env bash
# Runs every fuzz target (fuzz/*.cpp: the scene reader, the record readers, the record list)
# under ASan+UBSan for SECONDS each (default 3600), one after the other, growing the corpus in
# out/fuzz/corpus/.
# An input that crashes a target is copied into fuzz/regressions/<target>/, which the test
# suite replays from then on (fix the bug, commit the input). Exit 1 if any target crashed.
# Usage: fuzz.sh [SECONDS] [TARGET...]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-3600}
shift || true
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(fuzz_scene fuzz_record fuzz_record_list)
./scripts/build-sanitized.sh --target "${targets[@]}"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
found=0
for target in "${targets[@]}"; do
  corpus=out/fuzz/corpus/$target
  artifacts=out/fuzz/artifacts/$target
  rm -rf "$artifacts"
  mkdir -p "$corpus" "$artifacts"
  cp -n fuzz/corpus/"$target"/* fuzz/regressions/"$target"/* "$corpus"/ 2>/dev/null || true
  echo "== $target: ${seconds} s"
  # -timeout: an input taking 10 s is a finding too (unbounded work); -rss_limit_mb likewise.
  if ! build-asan/fuzz/"$target" "$corpus" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
       -max_len=65536 -print_final_stats=1 -artifact_prefix="$artifacts/" 2>&1 | tail -n 40; then
    found=1
  fi
  for crash in "$artifacts"/*; do
    [ -e "$crash" ] || continue
    cp "$crash" fuzz/regressions/"$target"/
    echo "FOUND: $crash (kept in fuzz/regressions/$target/)"
    found=1
  done
done
exit "$found"
