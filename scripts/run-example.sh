#!/usr/bin/env bash
# Sets up (bootstrap.sh) and runs the published example: modes of both buildings, the scene
# check, the time-history run at the paper's 0.20 m gap and at 0.50 m, its report page and a film
# of its first bounces, and the figure of level 7 (floor 7 of both) with the 0.50 m run in grey
# underneath.
set -euo pipefail
cd "$(dirname "$0")/.."
# The program and the Python module only (the test command builds the ~70 test executables).
./scripts/bootstrap.sh --target pounding_cli --target _pounding
pounding=./build/apps/pounding
$pounding modes examples/paper/paper.toml --json out/paper/modes.json
$pounding check examples/paper/paper.toml
$pounding run examples/paper/paper.toml --gap 0.5 --out out/paper-gap0.50
$pounding run examples/paper/paper.toml --out out/paper
$pounding report out/paper    # out/paper/report.html
$pounding animate out/paper --start 5.5 --end 7.5 --speed 0.25   # out/paper/level7.gif (.mp4 with ffmpeg)
# The figure's bounce inset needs the flights between impacts (milliseconds long), so the
# figure is drawn from the same run with history every 0.1 ms at level 7: the scene with an
# [output] table added and the record's path made absolute (the copy lives in out/).
figure=out/paper-figure
mkdir -p "$figure"
sed "s#^file = \"\.\./records/#file = \"$PWD/examples/records/#" examples/paper/paper.toml > "$figure/scene.toml"
printf '\n[output]\nhistory_floors = [7]\nhistory_interval_s = 1e-4\n' >> "$figure/scene.toml"
$pounding run "$figure/scene.toml" --out "$figure/run" > /dev/null
/usr/bin/python3 tools/plot_run.py "$figure/run" --compare out/paper-gap0.50 --out out/paper/level7.png
