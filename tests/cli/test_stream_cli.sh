#!/usr/bin/env bash
# What a long run leaves when it is stopped: killed outright (SIGKILL), its history and impacts
# are on disk as .partial files with their header and the rows computed until shortly before, and
# there is no summary.json; stopped by SIGTERM, it ends with status interrupted and the usual
# three files, the history reaching end_s. Usage: test_stream_cli.sh POUNDING_BINARY SOURCE_DIR
set -uo pipefail
pounding=$1
source_dir=$2
# 90 s of a dense record with BDF: several seconds of run, so it is still going when stopped.
scene=$source_dir/validation/extreme/cases/long-dense-record.toml
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# Starts a run into $work/$1 in the background (its pid in $pid) and waits until its streamed
# file $2 holds $3 lines. Waiting for rows, not for a fixed time, keeps the checks meaningful on a
# fast or a loaded machine.
start_and_wait_for_lines() {
  "$pounding" run "$scene" --method cvode-bdf --out "$work/$1" > "$work/$1.txt" 2>&1 &
  pid=$!
  local waited=0
  while [ "$(cat "$work/$1/$2" 2> /dev/null | wc -l)" -lt "$3" ] && [ $waited -lt 4000 ]; do
    kill -0 $pid 2> /dev/null || break
    sleep 0.05
    waited=$((waited + 1))
  done
}

# Killed once two impacts (at 36.3 s of the record, about 3 s into a Release run; waiting at most
# 200 s leaves room for the sanitizer build) are on disk, in a folder that held an earlier run's
# outputs: they are removed when the run starts, so none is taken for the killed run's.
mkdir -p "$work/killed"
for earlier in summary.json history.csv impacts.csv contacts_history.csv; do echo earlier > "$work/killed/$earlier"; done
start_and_wait_for_lines killed impacts.csv.partial 3
if kill -KILL "$pid" 2> /dev/null; then
  wait "$pid" 2> /dev/null
  for earlier in summary.json history.csv impacts.csv contacts_history.csv; do
    [ ! -e "$work/killed/$earlier" ] || fail "a killed run left $earlier (an earlier run's) beside its .partial files"
  done
  /usr/bin/python3 - "$work/killed" <<'PY' || fail "the killed run's history.csv.partial / impacts.csv.partial"
import sys
folder = sys.argv[1]
lines = open(f"{folder}/history.csv.partial").read().split("\n")
header = lines[0].split(",")
assert header[0] == "t_s" and len(header) > 1, header
rows = [l.split(",") for l in lines[1:-1]]  # the last line may be cut off by the kill
assert all(len(r) == len(header) for r in rows), "a row with the wrong number of values"
times = [float(r[0]) for r in rows]
assert all(a < b for a, b in zip(times, times[1:])), "times not increasing"
# The history is flushed at least every second: it reaches the impacts, written up to the kill.
impacts = [l.split(",") for l in open(f"{folder}/impacts.csv.partial").read().split("\n")]
assert impacts[0][:2] == ["t_s", "level"], impacts[0]
assert len(rows) > 3000 and times[-1] > float(impacts[2][0]) - 1.0, (len(rows), times[-1], impacts[2][0])
print(f"killed at t = {times[-1]} s of the record: {len(rows)} history rows, {len(impacts) - 2} impacts on disk")
PY
else
  fail "the run ended before it could be killed; nothing was checked"
fi

start_and_wait_for_lines stopped history.csv.partial 500
if kill -TERM "$pid" 2> /dev/null; then
  wait "$pid"
  code=$?
  [ "$code" -eq 3 ] || fail "a run stopped by SIGTERM exited $code, expected 3"
  ls "$work"/stopped/*.partial > /dev/null 2>&1 && fail "an interrupted run left .partial files"
  /usr/bin/python3 - "$work/stopped" <<'PY' || fail "the interrupted run's outputs"
import csv, json, sys
folder = sys.argv[1]
s = json.load(open(f"{folder}/summary.json"))
assert s["status"] == "interrupted", s["status"]
rows = list(csv.reader(open(f"{folder}/history.csv")))
assert len(rows) > 500 and abs(float(rows[-1][0]) - s["end_s"]) < 0.011, (len(rows), rows[-1][0], s["end_s"])
impacts = list(csv.reader(open(f"{folder}/impacts.csv")))
assert len(impacts) - 1 == s["impact_count"], (len(impacts), s["impact_count"])
PY
else
  fail "the run ended before SIGTERM; nothing was checked"
fi

[ $failures -eq 0 ] && echo "all stream checks passed"
exit $failures
