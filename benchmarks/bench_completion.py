"""Times completing one object's unseen side (complete_object) and the visibility model it reads, on one-view
pybullet scenes; prints medians per object. One OpenMP thread unless --threads.

Each scene: one object on the table, seen by one simulated camera (640 x 480 unless --width/--height) 55 cm away
at 45 degrees (noise on, seeded), taken two ways:
- the depth image (the user's input: segment_depth, as GraspModel.synthesize takes a depth image, an organized
  cloud or an organized PCD): "visibility" is segment_depth's own step time for its model (VisibilityModel::
  from_depth of the median-filtered image, and the join rule's pooled image), "completion" complete_object on the
  largest object against that model;
- the same view's points with the camera as their viewpoint (segment_scene): "visibility" its step time
  (from_views of the voxelised cloud, table included: a spherical range image), "completion" as above.
The issue's target: visibility + completion < 5 ms per object.

    python benchmarks/bench_completion.py [--repeats 15] [--threads 1] [--width 640 --height 480]
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
    p.add_argument("--width", type=int, default=640, help="the camera's image width (px)")
    p.add_argument("--height", type=int, default=480, help="the camera's image height (px)")
    args = p.parse_args()
    os.environ["OMP_NUM_THREADS"] = str(args.threads)
    import graspmix
    import numpy as np
    from graspmix import _core, complete_object
    from graspmix.perception import segment_scene
    from graspmix.sim.acquisition import AcquisitionSettings, Camera, acquire

    print(machine_line(graspmix.__version__))
    print(f"one {args.width}x{args.height} view from {EYE}; medians of {args.repeats} runs")
    print(
        f"{'object':<20}{'input':<13}{'points':>7}{'visibility ms':>15}{'completion ms':>15}{'total ms':>10}"
        "  winner, completed"
    )
    totals: dict[str, list[float]] = {"depth image": [], "points": []}
    with tempfile.TemporaryDirectory() as tmp:
        for name, (urdf, yaw) in objects(Path(tmp)).items():
            q = (0.0, 0.0, np.sin(yaw / 2), np.cos(yaw / 2))
            cam = Camera(eye=EYE, width=args.width, height=args.height)
            settings = AcquisitionSettings(cameras=[cam], keep="scene", object_orientation=q)
            acq = acquire(urdf, noise=True, seed=1, settings=settings)
            depth = np.where(np.isfinite(acq.depth_images[0]), acq.depth_images[0], 0.0)
            pinhole, pose = cam.pinhole(), cam.pose()

            def image_scene(depth=depth, pinhole=pinhole, pose=pose):
                return _core.segment_depth(depth, pinhole, pose, None)

            def points_scene(acq=acq):
                return segment_scene(acq.points, acq.viewpoints).result

            for kind, segment in (("depth image", image_scene), ("points", points_scene)):
                result = segment()
                rows = np.asarray(result.objects[0].rows)  # objects are largest first
                pts = np.asarray(result.points)[rows]
                vis, plane = result.visibility, result.plane
                build = statistics.median(segment().step_seconds["visibility"] for _ in range(args.repeats))
                run = median_seconds(lambda p=pts, g=plane, v=vis: complete_object(p, g, v), args.repeats)
                c = complete_object(pts, plane, vis)
                totals[kind].append(build + run)
                print(
                    f"{name:<20}{kind:<13}{len(pts):>7}{1e3 * build:>15.2f}{1e3 * run:>15.2f}"
                    f"{1e3 * (build + run):>10.2f}  {c.kind.name}, {len(c.points)}"
                    f"{'  (' + c.warning + ')' if c.warning else ''}",
                    flush=True,
                )
    for kind, t in totals.items():
        print(f"median over objects, {kind}: {1e3 * statistics.median(t):.2f} ms (target < 5 ms)")
    print(f"load average after: {load_average()}")


if __name__ == "__main__":
    main()
