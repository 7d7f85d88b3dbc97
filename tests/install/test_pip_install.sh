#!/usr/bin/env bash
# `pip install .` into a fresh virtual environment VENV (Debian's packages visible, nothing
# downloaded), packaging the module BUILD_DIR has built (setup.py, POUNDING_BUILD_DIR). The Python
# tests then run with VENV's interpreter, without PYTHONPATH (python/CMakeLists.txt). Then a bare venv
# (no Debian packages) must be told that `wheel` is missing.
# Usage: test_pip_install.sh BUILD_DIR SOURCE_DIR VENV PYTHON
set -euo pipefail
build=$1 source=$2 venv=$3 python=$4
rm -rf "$venv"
"$python" -m venv --system-site-packages "$venv"
POUNDING_BUILD_DIR=$build "$venv/bin/python" -m pip install --quiet --no-build-isolation --no-deps --no-index \
  --disable-pip-version-check "$source"
# Imported from the environment, not from the source or build tree, in a folder holding neither.
cd "$venv"
env -u PYTHONPATH "$venv/bin/python" - "$venv" "$source" <<'PY'
import pathlib, sys
import pounding
where = pathlib.Path(pounding.__file__).resolve()
venv, source = (pathlib.Path(p).resolve() for p in sys.argv[1:])
print(f"pounding {pounding.__version__} imported from {where}")
if venv not in where.parents:
    sys.exit(f"FAIL: pounding was imported from {where}, not from the environment {venv}")
PY
# A Python without Debian's packages (a venv made without --system-site-packages: no wheel, no
# numpy) is told what is missing, not setuptools' "invalid command 'bdist_wheel'".
bare=$(mktemp -d)
trap 'rm -rf "$bare"' EXIT
"$python" -m venv "$bare/venv"
if said=$(POUNDING_BUILD_DIR=$build "$bare/venv/bin/python" -m pip install --no-build-isolation --no-deps --no-index \
            --disable-pip-version-check "$source" 2>&1); then
  echo "FAIL: pip install succeeded in a venv without wheel and numpy"
  exit 1
fi
if ! grep -q "has no \`wheel\`.*python3-wheel" <<< "$said"; then
  echo "FAIL: pip install without wheel did not name it:"
  echo "$said" | tail -5
  exit 1
fi
echo "pip install without wheel names it: $(grep -o "has no \`wheel\`[^.]*" <<< "$said" | head -1)"
