#!/usr/bin/env bash
# Regenerates python/graspmix/_core.pyi (type stubs of the C++ module) from a built module with
# pybind11-stubgen 3.0.0 (pip install pybind11-stubgen==3.0.0). Run after changing the bindings and
# commit the stub; tests/python/test_stubs.py fails when it falls behind the module.
#
#   scripts/make_stubs.sh [build-dir]     (default: build/ beside this folder)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${1:-$root/build}"
module=("$build"/_core*.so)
[ -f "${module[0]}" ] || { echo "make_stubs.sh: no _core*.so in $build; build the Python module first" >&2; exit 2; }
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
# The package from the source tree with the freshly built module, so the stub matches that build.
cp -r "$root/python/graspmix" "$tmp/graspmix"
rm -f "$tmp"/graspmix/_core*.so "$tmp/graspmix/_core.pyi"
cp "${module[0]}" "$tmp/graspmix/"
ln -s "$root/data" "$tmp/graspmix/data"  # the package reads its bundled data on import
PYTHONPATH="$tmp" python3 -m pybind11_stubgen graspmix._core --output-dir "$tmp/stubs" \
  --numpy-array-wrap-with-annotated --exit-code
cp "$tmp/stubs/graspmix/_core.pyi" "$root/python/graspmix/_core.pyi"
echo "wrote python/graspmix/_core.pyi"
