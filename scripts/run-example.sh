#!/usr/bin/env bash
# Sets up (bootstrap.sh) and runs the published example: the modes of both buildings and the
# check of the whole scene.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/bootstrap.sh
./build/apps/pounding modes examples/paper/paper.toml --json out/paper/modes.json
./build/apps/pounding check examples/paper/paper.toml
