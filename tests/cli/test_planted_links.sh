#!/usr/bin/env bash
# No command writes through a symbolic link planted in its output folder (a shared results
# folder): for every command, a link named like each of its temporary (.partial) and final
# outputs points at a file outside the folder; the run must leave every such file untouched and
# its own outputs as regular files. Usage: test_planted_links.sh POUNDING_BINARY SOURCE_DIR
set -uo pipefail
pounding=$1
source_dir=$(cd "$2" && pwd)
paper=$source_dir/examples/paper/paper.toml
record=$source_dir/examples/records/elcentro1940_ns_0.02s.AT2
# A build without the Python module (the sanitizer build) has no sweep and draws no spectrum.png.
has_python=0
[ -f "$(dirname "$pounding")/../python/pounding/sweep/__init__.py" ] && has_python=1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# plant FOLDER NAME...: FOLDER/NAME and FOLDER/NAME.partial become links to victims outside it.
plant() {
  local folder=$1; shift
  mkdir -p "$folder" "$work/victims"
  for name in "$@"; do
    for planted in "$name" "$name.partial"; do
      local victim="$work/victims/$(basename "$folder")-$planted"
      echo "VICTIM $planted" > "$victim"
      ln -sf "$victim" "$folder/$planted"
    done
  done
}

# check FOLDER NAME...: no victim changed; every NAME that exists is a regular file, not a link.
check() {
  local folder=$1; shift
  for victim in "$work/victims/$(basename "$folder")"-*; do
    local planted=${victim##*/$(basename "$folder")-}
    [ "$(cat "$victim")" = "VICTIM $planted" ] || fail "$(basename "$folder"): wrote through the link $planted"
  done
  for name in "$@"; do
    [ -L "$folder/$name" ] && fail "$(basename "$folder"): $name is still the planted link"
    [ -f "$folder/$name" ] || fail "$(basename "$folder"): $name was not written"
  done
}

run_outputs=(summary.json history.csv impacts.csv contacts_history.csv)
plant "$work/run" "${run_outputs[@]}"
"$pounding" run "$paper" --out "$work/run" > /dev/null 2>&1 || fail "run exited $?"
check "$work/run" "${run_outputs[@]}"

plant "$work/run-no-history" "${run_outputs[@]}"
"$pounding" run "$paper" --history off --out "$work/run-no-history" > /dev/null 2>&1 || fail "run --history off exited $?"
check "$work/run-no-history" summary.json impacts.csv

plant "$work/modes" m.json
"$pounding" modes "$paper" --json "$work/modes/m.json" > /dev/null 2>&1 || fail "modes exited $?"
check "$work/modes" m.json

gap_outputs=(gap.json gap.csv gap_history.csv gap_curve.csv)
plant "$work/gap" "${gap_outputs[@]}"
"$pounding" gap "$paper" --curve 2 --out "$work/gap" > /dev/null 2>&1 || fail "gap exited $?"
check "$work/gap" "${gap_outputs[@]}"

printf '%s\n' "$record" > "$work/list.txt"
plant "$work/records" records.json records.csv
"$pounding" gap "$source_dir/examples/paper/el-centro-true-time.toml" --records "$work/list.txt" \
  --out "$work/records" > /dev/null 2>&1 || fail "gap --records exited $?"
check "$work/records" records.json records.csv

spectrum_outputs=(spectrum.csv rotd.csv spectrum.json)
[ $has_python -eq 1 ] && spectrum_outputs+=(spectrum.png)
plant "$work/spectrum" "${spectrum_outputs[@]}"
"$pounding" spectrum "$record" "$record" --rotd --angle-step 45 --periods 0.5,1 --out "$work/spectrum" > /dev/null 2>&1 \
  || fail "spectrum exited $?"
check "$work/spectrum" "${spectrum_outputs[@]}"

# The probe file that proves a folder takes files is created afresh too.
mkdir -p "$work/probe"
echo "VICTIM" > "$work/probe-victim"
for pid in $(seq $$ $(($$ + 50))); do ln -sf "$work/probe-victim" "$work/probe/.pounding-write-test-$pid"; done
"$pounding" run "$paper" --history off --out "$work/probe" > /dev/null 2>&1 || fail "run into the probe folder exited $?"
[ "$(cat "$work/probe-victim")" = "VICTIM" ] || fail "the write probe truncated a file through a link"

# The sweep's table is appended to, never through a link: a planted sweep.csv is refused by name,
# and a planted sweep.json(.partial) is replaced, not followed.
if [ $has_python -eq 1 ]; then
  cat > "$work/sweep.toml" <<TOML
scenes = ["$paper"]
gaps_m = [0.2]
restitutions = [0.5]
methods = [{ name = "exact" }]
TOML
  plant "$work/sweep-json" sweep.json
  "$pounding" sweep "$work/sweep.toml" --serial --no-progress --out "$work/sweep-json" > /dev/null 2>&1 \
    || fail "sweep exited $?"
  check "$work/sweep-json" sweep.json sweep.csv
  plant "$work/sweep-csv" sweep.csv
  "$pounding" sweep "$work/sweep.toml" --serial --no-progress --out "$work/sweep-csv" > "$work/sweep-csv.txt" 2>&1
  status=$?
  [ $status -eq 2 ] && grep -q "sweep.csv is a symbolic link" "$work/sweep-csv.txt" \
    || fail "a planted sweep.csv: exit $status, $(head -c 300 "$work/sweep-csv.txt")"
  for victim in "$work/victims/sweep-csv"-*; do
    planted=${victim##*/sweep-csv-}
    [ "$(cat "$victim")" = "VICTIM $planted" ] || fail "sweep: wrote through the link $planted"
  done
fi

echo "$((failures == 0 ? 1 : 0)) passed, $((failures == 0 ? 0 : 1)) failed"
[ $failures -eq 0 ]
