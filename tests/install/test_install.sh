#!/usr/bin/env bash
# `cmake --install` into a fresh prefix, then a project outside this one (consumer/) found through
# find_package(pounding) and linked to pounding::pounding: it must build, and its periods and
# impact count for the paper scene must equal the installed program's (`modes --json`, `run`).
# Usage: test_install.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1 source=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"
for file in bin/pounding lib/libpounding.a include/pounding/analysis/run_scene.hpp \
            lib/cmake/pounding/poundingConfig.cmake; do
  [ -f "$work/prefix/$file" ] || { echo "FAIL: cmake --install did not install $file"; exit 1; }
done
# CMAKE_PREFIX_PATH only: the package must bring its dependencies itself.
cmake -S "$source/tests/install/consumer" -B "$work/consumer" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$work/prefix" > "$work/configure.log" || { cat "$work/configure.log"; exit 1; }
cmake --build "$work/consumer" > "$work/build.log" || { cat "$work/build.log"; exit 1; }

scene=$source/examples/paper/paper.toml
consumer=$("$work/consumer/consumer" "$scene")
"$work/prefix/bin/pounding" modes "$scene" --json "$work/modes.json" > /dev/null
"$work/prefix/bin/pounding" run "$scene" --out "$work/run" > /dev/null
/usr/bin/python3 - "$consumer" "$work/modes.json" "$work/run/summary.json" <<'PY'
import json, sys
t1, t2, impacts = sys.argv[1].split()
modes = [b["periods_s"][0] for b in json.load(open(sys.argv[2]))["buildings"]]
count = len(json.load(open(sys.argv[3]))["impacts"])
print(f"consumer: T1 {t1} s, T2 {t2} s, {impacts} impacts; program: {modes[0]} s, {modes[1]} s, {count}")
if [float(t1), float(t2)] != modes or int(impacts) != count:
    sys.exit("FAIL: the consumer linked to the installed library disagrees with the installed program")
PY
echo "ok: find_package(pounding) consumer built against $work/prefix"
