#!/usr/bin/env bash
# End-to-end checks of `pounding gap`: the files it writes and their keys, that the printed
# needed gap is the written one, the severity table, the plot script, a two-record set (rows,
# statistics against Python's, a failed record), and bad input exiting 2 with a message naming
# the option or the list line. Usage: test_gap_cli.sh POUNDING_BINARY SOURCE_DIR
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

# A record set of two records (one by a relative path, one with its own options), two threads.
true_time=$source_dir/examples/paper/el-centro-true-time.toml
records=$source_dir/examples/records
mkdir -p "$work/list"
cp "$records/elcentro1940_ns_0.02s.AT2" "$work/list/"
{
  echo "# two records"
  echo "elcentro1940_ns_0.02s.AT2"
  echo "$records/northridge1994_newhall360_peer_RSN1044.AT2 pga_g=0.25   # its own PGA"
} > "$work/list/set.txt"
"$pounding" gap "$true_time" --records "$work/list/set.txt" --threads 2 --out "$work/set" > "$work/set.txt" \
  2> "$work/set.err" || fail "gap --records exited $?"
grep -q "2/2 records done, 0 failed" "$work/set.err" || fail "no progress line: $(cat "$work/set.err")"
"$pounding" gap "$true_time" --out "$work/alone" > /dev/null 2>&1 || fail "gap of the true-time scene exited $?"
/usr/bin/python3 - "$work/set" "$work/set.txt" "$work/alone/gap.json" <<'PY' || fail "records.csv / records.json content"
import csv, json, math, re, statistics, sys
folder, printed, alone = sys.argv[1], open(sys.argv[2]).read(), json.load(open(sys.argv[3]))
rows = list(csv.DictReader(open(f"{folder}/records.csv")))
doc = json.load(open(f"{folder}/records.json"))
assert [r["record"] for r in rows] == ["elcentro1940_ns_0.02s.AT2", "northridge1994_newhall360_peer_RSN1044.AT2"], rows
assert all(r["status"] == "completed" for r in rows) and doc["failed"] == 0
assert [r["needed_gap_m"] for r in doc["records"]] == [float(r["needed_gap_m"]) for r in rows]
# The scene's own record, run in the set, gives the scene's needed gap and rules.
assert float(rows[0]["needed_gap_m"]) == alone["needed_gap_m"], (rows[0], alone["needed_gap_m"])
assert float(rows[0]["srss_m"]) == alone["rules"]["srss_m"]
assert abs(float(rows[0]["pga_g"]) - 0.32) < 1e-12 and abs(float(rows[1]["pga_g"]) - 0.25) < 1e-12
for key in ("needed_gap_m", "abs_m", "srss_m", "ddc_m"):
    x = [float(r[key]) for r in rows]
    s = doc["statistics"][key]
    logs = [math.log(v) for v in x]
    assert s["count"] == 2
    assert math.isclose(s["mean"], sum(x) / 2, rel_tol=1e-14) and math.isclose(s["median"], sum(x) / 2, rel_tol=1e-14)
    p84 = math.exp(statistics.mean(logs) + statistics.stdev(logs))  # stdev: divisor n - 1
    assert math.isclose(s["p84_lognormal"], p84, rel_tol=1e-12), (key, s, p84)
worst = max(rows, key=lambda r: float(r["needed_gap_m"]))
assert doc["worst"] == worst["record"]
line = rf"^Worst record: {re.escape(worst['record'])}, needed gap {float(worst['needed_gap_m']):.6f} m"
assert re.search(line, printed, re.M), printed
for r in rows:
    assert re.search(rf"^{re.escape(r['record'])} .* {float(r['needed_gap_m']):.6f} ", printed, re.M), r["record"]
PY

# A bad line stops the set before any run, naming the list file, the line and the field.
printf 'elcentro1940_ns_0.02s.AT2\nelcentro1940_ns_0.02s.AT2 pga_g=lots\n' > "$work/list/bad.txt"
"$pounding" gap "$true_time" --records "$work/list/bad.txt" --out "$work/bad-set" > /dev/null 2> "$work/bad-set.txt"
[ $? -eq 2 ] || fail "a bad record list should exit 2"
grep -q "bad.txt:2: pga_g = lots: expected a number" "$work/bad-set.txt" || fail "bad list message: $(cat "$work/bad-set.txt")"
# A record that cannot be read is a failed row, not a lost set: exit 3, both rows written.
printf 'elcentro1940_ns_0.02s.AT2\nset.txt\n' > "$work/list/unreadable.txt"
"$pounding" gap "$true_time" --records "$work/list/unreadable.txt" --out "$work/unreadable" > /dev/null 2>&1
[ $? -eq 3 ] || fail "a set with a failed record should exit 3"
grep -q '^"set.txt",.*,failed,' "$work/unreadable/records.csv" || fail "no failed row: $(cat "$work/unreadable/records.csv")"
grep -q '^"elcentro1940_ns_0.02s.AT2",.*,completed,' "$work/unreadable/records.csv" || fail "no completed row"
# plot_gap.py draws a record-set folder as the set (records.png), naming what did not complete.
/usr/bin/python3 "$source_dir/tools/plot_gap.py" "$work/set" > /dev/null || fail "plot_gap.py on a record set exited $?"
[ -s "$work/set/records.png" ] || fail "no records.png for the record set"
/usr/bin/python3 "$source_dir/tools/plot_gap.py" "$work/unreadable" --out "$work/unreadable.png" > /dev/null ||
  fail "plot_gap.py on a set with a failed record exited $?"
# The record options of run/check/gap name the option in their errors.
"$pounding" check "$true_time" --pga-g -0.3 > /dev/null 2> "$work/bad-pga.txt"
[ $? -eq 2 ] || fail "a bad --pga-g should exit 2"
grep -q -- "--pga-g = -0.3" "$work/bad-pga.txt" || fail "bad --pga-g message: $(cat "$work/bad-pga.txt")"
# A budget or a signal ends the contact-free runs with a named status: exit 3, the outputs say so.
"$pounding" gap "$scene" --max-wall-time 1e-9 --out "$work/budget" > "$work/budget.txt" 2>&1
[ $? -eq 3 ] || fail "gap over its wall-time budget should exit 3"
/usr/bin/python3 -c "import json,sys; d=json.load(open(sys.argv[1])); assert d['status']=='time_limit', d['status']" \
  "$work/budget/gap.json" || fail "gap.json status after the budget"
grep -q "lower bound" "$work/budget.txt" || fail "no lower-bound warning: $(cat "$work/budget.txt")"
"$pounding" gap "$true_time" --records "$work/list/set.txt" --max-wall-time 1e-9 --out "$work/budget-set" > /dev/null 2>&1
[ $? -eq 3 ] || fail "a record set over its budget should exit 3"
[ "$(grep -c ',time_limit,' "$work/budget-set/records.csv")" -eq 2 ] || fail "rows not time_limit: $(cat "$work/budget-set/records.csv")"
# SIGINT once the first record is done (its progress line is out): the second stops, interrupted.
"$pounding" gap "$true_time" --records "$work/list/set.txt" --threads 1 --out "$work/signal-set" > /dev/null \
  2> "$work/signal-set.err" &
signalled=$!
for _ in $(seq 600); do grep -q "1/2 records done" "$work/signal-set.err" 2> /dev/null && break; sleep 0.5; done
kill -INT $signalled
wait $signalled
[ $? -eq 3 ] || fail "an interrupted record set should exit 3"
grep -q ',interrupted,' "$work/signal-set/records.csv" || fail "no interrupted row: $(cat "$work/signal-set/records.csv" 2>&1)"

[ $failures -eq 0 ] && echo "all gap CLI checks passed"
exit $failures
