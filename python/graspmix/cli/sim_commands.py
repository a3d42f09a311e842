"""acquire, execute: simulated cameras and grasp execution."""

from __future__ import annotations

import argparse
import json
import time

from .. import _core
from ..io.checks import MAX_SIM_TIME
from ..model.settings import FeatureSettings
from .common import float_in, input_path, int_in, output_file, seed


def cmd_acquire(args: argparse.Namespace) -> int:
    from ..sim import acquisition

    settings = acquisition.AcquisitionSettings(keep=args.keep)
    post = acquisition.clean_up(voxel_size=args.voxel_size, seed=args.seed) if args.clean else None
    t0 = time.perf_counter()
    acq = acquisition.acquire(args.object, noise=args.noise, seed=args.seed, settings=settings, postprocess=post)
    dt = time.perf_counter() - t0
    _core.save_cloud(args.out, acq.points)
    print(
        f"acquired {len(acq.points)} points of {args.object} from {len(acq.cameras)} cameras "
        f"(noise {'on' if args.noise else 'off'}, seed {args.seed}"
        + (", cleaned up" + (", support plane removed" if acq.plane is not None else "") if args.clean else "")
        + f") in {dt * 1e3:.0f} ms; wrote {args.out}"
    )
    if args.picture:
        from ..viz import plot_depth_images

        plot_depth_images(acq, args.picture)
        print(f"wrote {args.picture}")
    return 0


def cmd_execute(args: argparse.Namespace) -> int:
    from .. import sim

    overrides = {
        k: v
        for k, v in (("grip_force", args.grip_force), ("lift_height", args.lift_height), ("hold_time", args.hold_time))
        if v is not None
    }
    r = sim.execute_file(args.object, args.grasps, rank=args.rank, hand=args.hand, **overrides)
    if args.json:
        print(json.dumps(dict(sim.result_dict(r), object=args.object, rank=args.rank)))
    else:
        print(
            f"grasp {args.rank} on {args.object}: {'SUCCESS' if r.success else 'FAILURE'} ({r.reason}); "
            f"object lifted {r.lift_height * 100:.1f} cm, {r.contact_count} contacts; "
            f"{r.steps} steps = {r.simulated_time:.2f} s simulated in {r.wall_time * 1e3:.0f} ms"
        )
    return 0


def add_parsers(sub) -> None:
    s = sub.add_parser("acquire", help="a stitched point cloud of an object from 4 simulated depth cameras (pybullet)")
    s.add_argument(
        "--object",
        type=input_path,
        required=True,
        help="object URDF: a path, or relative to pybullet_data (random_urdfs/012/012.urdf)",
    )
    s.add_argument("--noise", action="store_true", help="apply the depth noise model (sigma_p = 1 px, sigma_d = 1 mm)")
    s.add_argument("--seed", type=seed, default=0, help="seed of the noise")
    s.add_argument(
        "--keep",
        choices=["object", "scene"],
        default="object",
        help="object: the pixels that see the object (segmentation); scene: the support plane too",
    )
    s.add_argument("--out", type=output_file, required=True, help="output cloud (.pcd)")
    s.add_argument("--picture", type=output_file, help="also save a picture of the depth images (.png)")
    s.add_argument(
        "--clean",
        action="store_true",
        help="clean up: voxel grid, outlier removal, and (with --keep scene) support-plane removal",
    )
    s.add_argument(
        "--voxel-size",
        type=float_in(0.0),
        default=FeatureSettings.voxel_size,
        help=f"m, voxel grid of --clean (default {FeatureSettings.voxel_size})",
    )
    s.set_defaults(func=cmd_acquire)

    d = _core.SimSettings()  # the C++ defaults, for the help texts
    s = sub.add_parser("execute", help="execute a grasp from grasps.json on an object in Bullet physics")
    s.add_argument("--object", type=input_path, required=True, help="object URDF: a path, or relative to pybullet_data")
    s.add_argument("--grasps", type=input_path, required=True, help="grasps.json (format graspmix.grasps/1)")
    s.add_argument("--rank", type=int_in(1), default=1, help="which grasp (1 = the best)")
    s.add_argument("--hand", type=input_path, help="hand URDF (default: the bundled WSG 50)")
    s.add_argument("--grip-force", type=float_in(gt=0.0), help=f"N (default {d.grip_force:g})")
    s.add_argument("--lift-height", type=float_in(gt=0.0), help=f"m (default {d.lift_height:g})")
    s.add_argument(
        "--hold-time", type=float_in(0.0, MAX_SIM_TIME), help=f"s (default {d.hold_time:g}, at most {MAX_SIM_TIME:g})"
    )
    s.add_argument("--json", action="store_true", help="print the result as JSON")
    s.set_defaults(func=cmd_execute)
