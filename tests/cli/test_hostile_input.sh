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
refused "paper.toml: --record-dt = missing: the record $source_dir/examples/records/elcentro1940_ns_0.02s.AT2 is read as format 'single'" \
  run "$paper" --record "$source_dir/examples/records/elcentro1940_ns_0.02s.AT2" --record-format single --out "$work/o"

# Work bounded before it is allocated: a 10 000 x 10 000 column grid (10^8 columns from 150 kB of
# text) and a 20 003-vertex slab are refused at once, naming the key.
/usr/bin/python3 - "$paper" "$work" <<'PY'
import sys
paper, work = sys.argv[1], sys.argv[2]
scene = open(paper).read().replace('file = "../records/', f'file = "{paper.rsplit("/", 2)[0]}/records/')
xs = ", ".join(f"{-24 + i * 0.0024:.4f}" for i in range(10000))
grid = scene.replace("x = [-24.0, -18.0, -12.0, -6.0, 0.0]", f"x = [{xs}]", 1)
grid = grid.replace("y = [0.0, 5.0, 10.0, 15.0, 20.0]", f"y = [{xs}]", 1)
open(f"{work}/grid.toml", "w").write(grid)
vertices = ", ".join(f"[{-24 + 24 * i / 20000:.6f}, 0.0]" for i in range(20001))
slab = scene.replace("slab = [[-24.0, 0.0], [0.0, 0.0], [0.0, 20.0], [-24.0, 20.0]]",
                     f"slab = [{vertices}, [0.0, 20.0], [-24.0, 20.0]]", 1)
open(f"{work}/slab.toml", "w").write(slab)
PY
refused "building[1].column_grid[1] = {...}: 10000 x 10000 = 100000000 columns" check "$work/grid.toml"
refused "20003 vertices: a slab may have at most 1000" check "$work/slab.toml"
[ -e "$work/o/summary.json" ] && fail "a refused run wrote summary.json"

# Messages name the key the file holds, and cut what they echo.
/usr/bin/python3 - "$paper" "$work" <<'PY'
import sys
paper, work = sys.argv[1], sys.argv[2]
scene = open(paper).read().replace('file = "../records/', f'file = "{paper.rsplit("/", 2)[0]}/records/')
kobe = 'file = "' + paper.rsplit("/", 2)[0] + '/records/kobe1995_jma_ns_ew_0.005s_cms2.txt"\nformat = "single"'
open(f"{work}/column99.toml", "w").write(scene.replace(
    'file = "' + paper.rsplit("/", 2)[0] + '/records/elcentro1940_ns_0.02s.AT2"\nformat = "peer-at2"',
    kobe + "\naccel_column = 99", 1))
open(f"{work}/top.toml", "w").write(scene.replace("top_floor_mass_t = 530.0", "top_floor_mass_t = 0.9", 1))
open(f"{work}/grid_b.toml", "w").write(scene.replace("b_m = 0.45", "b_m = -0.45", 1))
open(f"{work}/long_key.toml", "w").write(scene.replace("[excitation]", "[excitation]\n" + "k" * 500000 + " = 1", 1))
PY
refused "column 99 was asked for (read as $work/column99.toml asks: excitation.format = single, excitation.accel_column = 99" \
  check "$work/column99.toml"
refused "building[1].top_floor_mass_t = 0.9: must lie in [1," check "$work/top.toml"
refused "building[1].column_grid[1].b_m = -0.45: must lie in (0, 5] m" check "$work/grid_b.toml"
refused "(500011 characters) = 1: unknown key" check "$work/long_key.toml"
[ "$(wc -c < "$work/out.txt")" -lt 2000 ] || fail "a 500 kB key gave a $(wc -c < "$work/out.txt")-byte message"
refused "--contact-law = \"kelvin\": does not run on method hht" run "$paper" --contact-law kelvin --method hht --out "$work/o"

# A record set interrupted while records wait: their rows say "not started" and leave the needed
# gap, level and floors empty (they showed the gap at rest, -7e-16 m, at level 1).
"$pounding" gap "$source_dir/examples/paper/el-centro-true-time.toml" --records "$source_dir/examples/records/set.txt" \
  --threads 1 --out "$work/set" > /dev/null 2>&1 &
set_pid=$!
sleep 0.5
kill -INT $set_pid
wait $set_pid
/usr/bin/python3 - "$work/set/records.csv" <<'PY' || fail "rows of records that never started"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
waiting = [r for r in rows if r["message"].startswith("not started")]
assert waiting, "no record was left waiting: nothing checked"
for r in waiting:
    assert r["status"] == "interrupted" and r["steps"] == "0", r
    assert r["needed_gap_m"] == r["level"] == r["floor_b1"] == r["floor_b2"] == r["t_s"] == "", r
PY

echo "$((failures == 0 ? 1 : 0)) passed, $((failures == 0 ? 0 : 1)) failed"
[ $failures -eq 0 ]
