#!/usr/bin/env bash
# Installs the Debian packages the project needs (only those missing), then configures and
# builds a Release tree in build/, the Python module in build/python/ (README, "Python").
# Arguments, if any, are build targets (e.g. `--target pounding_cli`): the example builds only
# the program and the module, the test command everything. Safe to run again: it redoes only
# what is out of date.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(g++ make cmake libsundials-dev libeigen3-dev libboost-test-dev libtomlplusplus-dev
          libcli11-dev nlohmann-json3-dev libfmt-dev python3-matplotlib python3-numpy python3-scipy
          libbenchmark-dev pybind11-dev python3-dev python3-pytest python3-distributed python3-tqdm
          python3-venv python3-pandas python3-lxml mkdocs mkdocs-material)
./scripts/install-packages.sh "${packages[@]}"

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$(nproc)" "$@"
