#!/usr/bin/env bash
# Sets up (bootstrap.sh), runs the work-precision study of the paper scene (about a minute) and
# draws its plot: out/paper-study/{study.csv,study.json,work-precision.png}.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/bootstrap.sh
./build/apps/pounding study examples/paper/paper.toml --out out/paper-study "$@"
/usr/bin/python3 tools/plot_study.py out/paper-study
