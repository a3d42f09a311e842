"""Writes data/mug.pcd: pybullet_data's mug on a table seen by the four simulated depth cameras
(noise-free), the table cropped to a 30 x 30 cm square around the mug, every point with the position of
the camera that saw it (vp_x vp_y vp_z); the scene model of `graspmix_cli synthesize` then finds the
table (the cameras are above it) and removes it.

    python3 scripts/make_example_clouds.py
"""

from pathlib import Path

import graspmix
import numpy as np
from graspmix.sim.acquisition import AcquisitionSettings, acquire

root = Path(__file__).resolve().parent.parent
scan = acquire("objects/mug.urdf", noise=False, seed=0, settings=AcquisitionSettings(keep="scene"))
P = scan.points
keep = (np.abs(P[:, 0]) < 0.15) & (np.abs(P[:, 1]) < 0.15) & (P[:, 2] > -0.01) & (P[:, 2] < 0.3)
graspmix.save_cloud(
    str(root / "data" / "mug.pcd"), P[keep], encoding="binary_compressed", viewpoints=scan.viewpoints[keep]
)
print(f"wrote data/mug.pcd: {keep.sum()} points")
