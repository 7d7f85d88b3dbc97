#!/usr/bin/env bash
# Installs the Debian packages the project needs (only those missing), then configures and
# builds a Release tree in build/. Safe to run again: it redoes only what is out of date.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(g++ make cmake libsundials-dev libeigen3-dev libboost-test-dev libtomlplusplus-dev
          libcli11-dev nlohmann-json3-dev libfmt-dev python3-matplotlib libbenchmark-dev)
missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "Installing: ${missing[*]}"
  sudo_cmd=()
  [ "$(id -u)" -ne 0 ] && sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y --no-install-recommends "${missing[@]}"
fi

cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$(nproc)"
