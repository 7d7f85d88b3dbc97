#!/usr/bin/env bash
# End-to-end checks of `pounding gap`: the files it writes and their keys, that the printed
# needed gap is the written one, the severity table, the plot script, and bad input exiting 2
# with a message naming the option. Usage: test_gap_cli.sh POUNDING_BINARY SOURCE_DIR
set -uo pipefail
pounding=$1
source_dir=$2
scene=$source_dir/examples/paper/paper.toml
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

"$pounding" gap "$scene" --curve 3 --threads 2 --out "$work/gap" > "$work/gap.txt" 2> /dev/null || fail "gap exited $?"
for f in gap.json gap.csv gap_history.csv gap_curve.csv; do [ -s "$work/gap/$f" ] || fail "missing $f"; done
/usr/bin/python3 - "$work/gap" "$work/gap.txt" <<'PY' || fail "gap.json / gap.csv content"
import csv, hashlib, json, re, sys
folder, printed = sys.argv[1], open(sys.argv[2]).read()
g = json.load(open(f"{folder}/gap.json"))
for key in ("needed_gap_m", "floor", "t_s", "levels", "rules", "pair", "modes", "rho", "unconservative"):
    assert key in g, key
assert set(g["rules"]) == {"abs_m", "srss_m", "ddc_m"}, g["rules"]
levels = list(csv.DictReader(open(f"{folder}/gap.csv")))
assert len(levels) == len(g["levels"]) == 7
assert max(float(r["needed_gap_m"]) for r in levels) == g["needed_gap_m"]
assert g["floor"] == [g["level"], g["level"]]
# The printed needed gap (m, 6 decimals) is the written one; every rule is printed with its verdict.
m = re.search(r"^  ([0-9.]+) m at level (\d+)", printed, re.M)
assert m and abs(float(m.group(1)) - g["needed_gap_m"]) < 5e-7 and int(m.group(2)) == g["level"], printed
p = g["provenance"]
assert p["scene_sha256"] == hashlib.sha256(open(p["scene_file"], "rb").read()).hexdigest() and " gap " in p["command_line"], p
for rule in ("ABS", "SRSS", "DDC"):
    assert re.search(rf"^  {rule} +[0-9.]+ m +(UNCONSERVATIVE|conservative)", printed, re.M), rule
short = {u["rule"] for u in g["unconservative"]}
assert short == {r for r, k in (("ABS", "abs_m"), ("SRSS", "srss_m"), ("DDC", "ddc_m")) if g["rules"][k] < g["needed_gap_m"]}
curve = list(csv.DictReader(open(f"{folder}/gap_curve.csv")))
assert [float(r["gap_m"]) for r in curve] == [g["needed_gap_m"] * k / 3 for k in range(3)], curve
assert all(int(r["impacts"]) > 0 for r in curve)
history = list(csv.DictReader(open(f"{folder}/gap_history.csv")))
column = f"touch_gap_level_{g['level']}_m"
assert max(float(r[column]) for r in history) <= g["needed_gap_m"]
PY
/usr/bin/python3 "$source_dir/tools/plot_gap.py" "$work/gap" --out "$work/gap.png" > /dev/null || fail "plot_gap.py exited $?"
[ -s "$work/gap.png" ] || fail "no gap.png"

"$pounding" gap "$scene" --rtol -1 --out "$work/bad" > /dev/null 2> "$work/bad.txt"
[ $? -eq 2 ] || fail "bad --rtol should exit 2"
grep -q -- "--rtol = -1" "$work/bad.txt" || fail "bad --rtol message: $(cat "$work/bad.txt")"
# An unwritable --out is refused before the runs (exit 2, naming the option), with nothing printed.
touch "$work/a-file"
"$pounding" gap "$scene" --out "$work/a-file/gap" > "$work/bad-out.txt" 2> "$work/bad-err.txt"
[ $? -eq 2 ] || fail "unwritable --out should exit 2"
grep -q -- "--out = $work/a-file/gap: cannot create this folder" "$work/bad-err.txt" || fail "unwritable --out message: $(cat "$work/bad-err.txt")"
[ ! -s "$work/bad-out.txt" ] || fail "gap ran before refusing its --out"
"$pounding" gap "$work/missing.toml" > /dev/null 2>&1
[ $? -eq 2 ] || fail "missing scene should exit 2"

[ $failures -eq 0 ] && echo "all gap CLI checks passed"
exit $failures
