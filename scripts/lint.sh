#!/usr/bin/env bash
# Style and layering checks, run by scripts/test.sh (so CI fails on unformatted code):
#   clang-format (.clang-format) on every C++ file, ruff (pyproject.toml) on every Python file, and the
#   C++ layering of docs/design.md. `bash scripts/lint.sh --fix` formats in place instead of checking.
set -euo pipefail
cd "$(dirname "$0")/.."
PY=${PYTHON:-python3}
mapfile -t CXX < <(git ls-files '*.cpp' '*.hpp' 2>/dev/null || find include src tests examples python -name '*.[ch]pp')
PYDIRS=(python tests scripts benchmarks)
if [ "${1:-}" = "--fix" ]; then
  clang-format -i "${CXX[@]}"
  $PY -m ruff check --fix --exit-zero --quiet "${PYDIRS[@]}"  # what it cannot fix, the check below reports
  $PY -m ruff format --quiet "${PYDIRS[@]}"
  exit 0
fi
echo "[lint] clang-format on ${#CXX[@]} C++ files"
clang-format --dry-run --Werror "${CXX[@]}"
echo "[lint] ruff"
$PY -m ruff check "${PYDIRS[@]}"
$PY -m ruff format --check "${PYDIRS[@]}"
echo "[lint] layers"
$PY scripts/check_layers.py
