#!/usr/bin/env bash
# Writes data/scenes/packed4.json and .pcd: four objects of the development list (data/objects/clutter_dev.txt)
# packed on a table, seen by the one simulated 640x480 depth camera (noise-free, table kept: the whole image,
# organized 640 x 480 with NaN where nothing was hit, in the world frame, the camera's pose as the PCD VIEWPOINT).
# The README's first command synthesises grasps on one of them.
set -euo pipefail
cd "$(dirname "$0")/.."
graspmix_cli scene --objects 4 --mode packed --seed 0 --object-list data/objects/clutter_dev.txt \
  --out data/scenes/packed4.json
graspmix_cli acquire --scene data/scenes/packed4.json --encoding binary_compressed --out data/scenes/packed4.pcd
