#!/usr/bin/env bash
# `pip install .` into a fresh virtual environment VENV (Debian's packages visible, nothing
# downloaded), packaging the module BUILD_DIR has built (setup.py, POUNDING_BUILD_DIR). The Python
# tests then run with VENV's interpreter, without PYTHONPATH (python/CMakeLists.txt).
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
