#!/usr/bin/env bash
# Runs every test: the C++ suite with ctest (built by scripts/install.sh in ./build) and pytest.
set -euo pipefail
cd "$(dirname "$0")/.."
PY=${PYTHON:-python3}
echo "[test] lint (formatting, lint, C++ layering)"
bash scripts/lint.sh
echo "[test] ctest"
ctest --test-dir build --output-on-failure -j2
echo "[test] pytest"
# Run from a neutral directory so the installed package, not the source tree, is imported.
(cd tests/python && $PY -m pytest -q -p no:cacheprovider .)
