#!/usr/bin/env bash
# Sets up (bootstrap.sh), runs the work-precision study of the paper scene (about a minute) and
# draws its plot: out/paper-study/{study.csv,study.json,machine.txt,work-precision.png}.
# machine.txt records, at study time, the processor and core count the timings were taken on
# and the load average before and after (a busy machine makes every run slower).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/bootstrap.sh
out=out/paper-study
mkdir -p "$out"
{
  echo "cpu: $(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1)"
  echo "cores: $(nproc --all)"
  echo "load_before: $(cut -d ' ' -f 1-3 /proc/loadavg)"
} > "$out/machine.txt.partial"
./build/apps/pounding study examples/paper/paper.toml --out "$out" "$@"
echo "load_after: $(cut -d ' ' -f 1-3 /proc/loadavg)" >> "$out/machine.txt.partial"
mv "$out/machine.txt.partial" "$out/machine.txt"
/usr/bin/python3 tools/plot_study.py "$out"
