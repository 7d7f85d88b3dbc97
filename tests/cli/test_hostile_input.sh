#!/usr/bin/env bash
# Absurd input refused with exit 2 and a message naming the option or the file's line, never run:
# NUL bytes in a record, a record list and a scene; a denormal time step; integers that overflow;
# empty option values; unbounded repeat counts; an acceleration column that is the time column;
# an unknown command. Usage: test_hostile_input.sh POUNDING_BINARY SOURCE_DIR
set -uo pipefail
pounding=$1
source_dir=$(cd "$2" && pwd)
paper=$source_dir/examples/paper/paper.toml
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# refused WORDS ARGS...: exit 2, and the message holds WORDS (a fixed string).
refused() {
  local words=$1; shift
  "$pounding" "$@" > "$work/out.txt" 2>&1
  local status=$?
  [ $status -eq 2 ] && grep -qF -- "$words" "$work/out.txt" \
    || fail "$* : exit $status, expected 2 with '$words': $(head -c 300 "$work/out.txt")"
}

printf '0.0 0.0\n0.02 0.1\0 9\n0.04 0.2\n' > "$work/nul.txt"
refused "nul.txt: line 2: holds a NUL byte" run "$paper" --record "$work/nul.txt" --record-format columns --out "$work/o"
printf '%s\n' "$work/nul.txt" > "$work/list.txt"
printf 'x\0y\n' >> "$work/list.txt"
refused "list.txt:2" gap "$paper" --records "$work/list.txt" --out "$work/o"
{ cat "$paper"; printf '# \0\n'; } > "$work/scene.toml"
refused "holds a NUL byte" check "$work/scene.toml"
printf '0 1\n0.02 2\n0.04 3\n' > "$work/two.txt"
refused "is the time column" run "$paper" --record "$work/two.txt" --record-format columns --record-column 1 --out "$work/o"
refused "--record-dt = 1e-320: must lie in [1e-05, 1] s" run "$paper" --record-dt 1e-320 --out "$work/o"
refused "--max-steps: Value 99999999999999999999 not in range" run "$paper" --max-steps 99999999999999999999 --out "$work/o"
refused "--order: Value 2147483648 not in range" run "$paper" --method cvode-bdf --order 2147483648 --out "$work/o"
refused "--gap: an empty value is not allowed" run "$paper" --gap ''
refused "--out: an empty value is not allowed" run "$paper" --out ''
refused "--json: an empty value is not allowed" modes "$paper" --json ''
refused "--count: Value 0 not in range 1 to 10000" modes "$paper" --count 0
refused "--repeat: Value 1000000000 not in range 1 to 100" study "$paper" --repeat 1000000000
refused "unknown command 'frobnicate'" frobnicate
[ -e "$work/o/summary.json" ] && fail "a refused run wrote summary.json"

echo "$((failures == 0 ? 1 : 0)) passed, $((failures == 0 ? 0 : 1)) failed"
[ $failures -eq 0 ]
