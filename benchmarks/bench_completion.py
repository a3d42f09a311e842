"""Times completing one object's unseen side (complete_object) and the visibility model it reads, on one-view
pybullet scenes; prints medians per object. One OpenMP thread unless --threads.

Each scene: one object on the table, seen by one simulated camera 55 cm away at 45 degrees (noise on, seeded),
segmented by segment_scene; "visibility" is the scene's model built as segment_scene builds it
(the median of segment_scene's own step time for it: from_views of the voxelised cloud, table included), "completion" is complete_object on the largest object.
The issue's target: visibility + completion < 5 ms per object.

    python benchmarks/bench_completion.py [--repeats 15] [--threads 1]
"""

from __future__ import annotations

import argparse
import os
import statistics
import tempfile
from pathlib import Path

from bench_common import load_average, machine_line, median_seconds

SHAPE_URDF = """<?xml version="1.0"?>
<robot name="shape"><link name="base">
  <visual><geometry>{g}</geometry></visual><collision><geometry>{g}</geometry></collision>
  <inertial><mass value="0.2"/><inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial>
</link></robot>"""

EYE = (0.0, -0.39, 0.44)


def objects(folder: Path) -> dict[str, tuple[str, float]]:
    """name -> (urdf, yaw): boxes and a cylinder written here, pybullet_data's mug and duck."""
    shapes = {
        "box 9x6x10 cm": '<box size="0.09 0.06 0.1"/>',
        "box 5x5x5 cm": '<box size="0.05 0.05 0.05"/>',
        "cylinder r4 h11 cm": '<cylinder radius="0.04" length="0.11"/>',
    }
    out = {}
    for i, (name, g) in enumerate(shapes.items()):
        path = folder / f"shape{i}.urdf"
        path.write_text(SHAPE_URDF.format(g=g))
        out[name] = (str(path), 0.3)
    out["mug"] = ("objects/mug.urdf", 0.0)
    out["duck"] = ("duck_vhacd.urdf", 0.5)
    return out


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeats", type=int, default=15)
    p.add_argument("--threads", type=int, default=1, help="OMP_NUM_THREADS (set before graspmix loads)")
    args = p.parse_args()
    os.environ["OMP_NUM_THREADS"] = str(args.threads)
    import graspmix
    import numpy as np
    from graspmix import complete_object
    from graspmix.perception import segment_scene
    from graspmix.sim.acquisition import AcquisitionSettings, Camera, acquire

    print(machine_line(graspmix.__version__))
    print(f"one view from {EYE}; medians of {args.repeats} runs")
    print(f"{'object':<20}{'points':>8}{'visibility ms':>15}{'completion ms':>15}{'total ms':>10}  winner, completed")
    totals = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, (urdf, yaw) in objects(Path(tmp)).items():
            q = (0.0, 0.0, np.sin(yaw / 2), np.cos(yaw / 2))
            settings = AcquisitionSettings(cameras=[Camera(eye=EYE)], keep="scene", object_orientation=q)
            acq = acquire(urdf, noise=True, seed=1, settings=settings)
            scene = segment_scene(acq.points, acq.viewpoints)
            obj = scene.objects[scene.select("largest")[0]]
            vis = scene.result.visibility
            step = [
                segment_scene(acq.points, acq.viewpoints).result.step_seconds["visibility"] for _ in range(args.repeats)
            ]
            build = statistics.median(step)
            run = median_seconds(lambda o=obj, s=scene, v=vis: complete_object(o.points, s.plane, v), args.repeats)
            c = complete_object(obj.points, scene.plane, vis)
            totals.append(build + run)
            print(
                f"{name:<20}{len(obj.points):>8}{1e3 * build:>15.2f}{1e3 * run:>15.2f}{1e3 * (build + run):>10.2f}"
                f"  {c.kind.name}, {len(c.points)}{'  (' + c.warning + ')' if c.warning else ''}",
                flush=True,
            )
    print(f"median over objects: {1e3 * statistics.median(totals):.2f} ms (target < 5 ms)")
    print(f"load average after: {load_average()}")


if __name__ == "__main__":
    main()
