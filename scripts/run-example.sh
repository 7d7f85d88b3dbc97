#!/usr/bin/env bash
# Sets up (bootstrap.sh) and runs the published example: modes of both buildings, the scene
# check, the time-history run at the paper's 0.20 m gap and at 0.50 m, and the figure of
# level 7 (floor 7 of both) with the 0.50 m run in grey underneath.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/bootstrap.sh
pounding=./build/apps/pounding
$pounding modes examples/paper/paper.toml --json out/paper/modes.json
$pounding check examples/paper/paper.toml
$pounding run examples/paper/paper.toml --gap 0.5 --out out/paper-gap0.50
$pounding run examples/paper/paper.toml --out out/paper
/usr/bin/python3 tools/plot_run.py out/paper --compare out/paper-gap0.50
