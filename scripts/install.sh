#!/usr/bin/env bash
# Installs everything graspmix needs on a Debian machine and builds it: the Debian -dev packages
# (idempotent: apt-get skips what is there), the Python packages, then graspmix itself with its
# C++ tests, in ./build so that scripts/test.sh runs ctest there without building again.
set -euo pipefail
cd "$(dirname "$0")/.."

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi

# Eigen (mixtures, SE(3)), PCL (clouds, features), liblzf (binary_compressed PCD files), FCL (collision expert), OctoMap (occupancy of the scene), Bullet with its extras
# (simulated execution), urdfdom (hands), assimp (STL/OBJ meshes), qhull (convex hulls of meshes),
# GoogleTest (ctest), and the toolchain to build against them; Chromium, in which a test opens the interactive
# grasp view (graspmix_cli plot --html) headless and checks its screenshot.
DEBS=(build-essential pkg-config libeigen3-dev libpcl-dev liblzf-dev libfcl-dev liboctomap-dev libbullet-dev libbullet-extras-dev
      liburdfdom-dev libtinyxml-dev libassimp-dev libqhull-dev libgtest-dev chromium)
missing=()
for p in "${DEBS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "[install] apt-get install ${missing[*]}"
  $SUDO apt-get update
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y --no-install-recommends "${missing[@]}"
else
  echo "[install] Debian packages already installed"
fi

PY=${PYTHON:-python3}
export PIP_BREAK_SYSTEM_PACKAGES=1 PIP_DISABLE_PIP_VERSION_CHECK=1
echo "[install] Python packages"
$PY -m pip install --quiet -r requirements.txt

echo "[install] building graspmix (C++ library, Python module, C++ tests) in ./build"
# --no-build-isolation so the build directory is reused across installs (incremental rebuilds).
$PY -m pip install --quiet --no-build-isolation \
  -Cbuild-dir=build -Ccmake.define.GRASPMIX_BUILD_TESTS=ON .
echo "[install] done: $(command -v graspmix_cli)"
