"""acquire, execute: simulated cameras and grasp execution."""

from __future__ import annotations

import argparse
import json
import time

import numpy as np

from .. import _core
from ..io.checks import MAX_SIM_TIME
from ..model.grasps import grasp_by_rank
from ..model.settings import FeatureScale
from .common import (
    CliError,
    float_in,
    given,
    input_path,
    int_in,
    output_file,
    parse_floats,
    picture_file,
    png_file,
    seed,
    urdf_path,
)


def _scene_of(args: argparse.Namespace):
    """The scene of --scene, or --object alone at --object-pose (default: its rest pose at the origin)."""
    from ..sim import execution, scenes

    pose = getattr(args, "object_pose", None)
    if args.scene:
        if pose is not None:
            raise CliError("--object-pose goes with --object, not --scene (the scene file holds the poses)")
        return scenes.SceneSpec.load(args.scene)
    execution.load_object(args.object)  # the URDF checked whole before pybullet reads it
    pose = execution.rest_pose(args.object) if pose is None else parse_floats(pose, 7, "--object-pose")
    return scenes.SceneSpec([scenes.PlacedObject(args.object, pose)]).check()


def cmd_acquire(args: argparse.Namespace) -> int:
    from ..sim import acquisition, scene_camera

    if args.voxel_size is not None and not args.clean:
        raise CliError("--voxel-size is the voxel grid of --clean: give --clean too, or drop --voxel-size")
    if args.out is None and args.depth_out is None:
        raise CliError("give --out (the cloud) or --depth-out (the depth image), or both")
    if args.depth_out is not None and args.views != 1:
        raise CliError(f"--depth-out writes one camera's depth image: give --views 1 (got --views {args.views})")
    spec = _scene_of(args)
    post = acquisition.clean_up(**given(args, "voxel_size"), seed=args.seed) if args.clean else None
    t0 = time.perf_counter()
    acq = scene_camera.acquire_scene(spec, views=args.views, noise=args.noise, seed=args.seed, keep=args.keep)
    if post is not None:
        acq = post(acq)
    dt = time.perf_counter() - t0
    # One camera: its pose (optical frame: x right, y down, z forward) is the cloud's VIEWPOINT, and the whole image
    # is written organized (width x height, NaN where nothing was hit): what a driver gives, segmented in image
    # space. Several: each point carries the position of the camera that saw it (vp_x vp_y vp_z).
    viewpoint = acq.cameras[0].pose() if len(acq.cameras) == 1 else None
    per_point = acq.viewpoints if viewpoint is None else None
    points, size = acq.points, {}
    if viewpoint is not None and args.keep == "scene" and not args.clean:
        depth = acq.depth_images[0]
        points = acq.per_pixel(acq.points, np.nan)  # every return at its pixel, NaN where nothing was hit
        size = {"width": depth.shape[1], "height": depth.shape[0]}
    what = args.scene or args.object
    print(
        f"acquired {len(acq.points)} points of {what} ({len(spec.objects)} object(s), "
        f"{'table and objects' if args.keep == 'scene' else 'objects only'}) from {len(acq.cameras)} camera(s) "
        f"(noise {'on' if args.noise else 'off'}, seed {args.seed}"
        + (", cleaned up" + (", support plane removed" if acq.plane is not None else "") if args.clean else "")
        + f") in {dt * 1e3:.0f} ms"
    )
    if args.out is not None:
        _core.save_cloud(args.out, points, encoding=args.encoding, viewpoint=viewpoint, viewpoints=per_point, **size)
        print(
            f"wrote {args.out}"
            + (
                f" (viewpoint {', '.join(f'{v:.3f}' for v in viewpoint[:3])})"
                if viewpoint
                else " (per-point viewpoints)"
            )
            + (f", organized {size['width']} x {size['height']}" if size else "")
        )
    if args.depth_out is not None:
        from ..perception import write_depth

        depth, camera = acq.depth_images[0], acq.cameras[0]
        c = camera.pinhole()
        write_depth(args.depth_out, depth)
        print(
            f"wrote {args.depth_out} ({depth.shape[1]} x {depth.shape[0]}, 16-bit millimetres, 0: no return); give it as"
            f" --depth {args.depth_out} --intrinsics {c.fx:.9g},{c.fy:.9g},{c.cx:.9g},{c.cy:.9g}"
            f" --camera-pose={','.join(f'{v:.9g}' for v in camera.pose())}"
        )
    if args.picture:
        from ..viz import plot_depth_images

        plot_depth_images(acq, args.picture)
        print(f"wrote {args.picture}")
    return 0


def cmd_execute(args: argparse.Namespace) -> int:
    from .. import sim
    from ..sim import scenes

    overrides = {
        k: v
        for k, v in (("grip_force", args.grip_force), ("lift_height", args.lift_height), ("hold_time", args.hold_time))
        if v is not None
    }
    spec = _scene_of(args)
    doc, h = sim.execution.grasps_and_hand(args.grasps, args.hand)
    settings = sim.make_settings(None, **overrides)
    ex = scenes.execute_in_scene(spec, grasp_by_rank(doc, args.rank), hand=h, closing=args.closing, settings=settings)
    if args.out_scene:
        ex.remaining.save(args.out_scene)
    r = ex.result
    names = [o.urdf for o in spec.objects]
    if args.json:
        print(
            json.dumps(
                dict(
                    sim.result_dict(r),
                    lifted=ex.lifted,
                    lifted_objects=[names[i] for i in ex.lifted],
                    moved=[float(m) for m in ex.moved],
                    objects=names,
                    rank=args.rank,
                    closing=args.closing,
                )
            )
        )
        return 0
    print(
        f"grasp {args.rank} ({args.closing} closing): {'SUCCESS' if r.success else 'FAILURE'} ({r.reason}); "
        + (f"lifted {', '.join(f'{i}: {names[i]}' for i in ex.lifted)}" if ex.lifted else "nothing lifted")
        + f" ({r.lift_height * 100:.1f} cm), {r.contact_count} contacts; "
        f"{r.steps} steps = {r.simulated_time:.2f} s simulated in {r.wall_time * 1e3:.0f} ms"
    )
    for i, m in enumerate(ex.moved):
        if i not in ex.lifted:
            print(f"  object {i} ({names[i]}) moved {m * 100:.1f} cm")
    if args.out_scene:
        print(f"wrote {args.out_scene} ({len(ex.remaining.objects)} object(s) left)")
    return 0


def _add_scene_source(s, what: str) -> None:
    g = s.add_mutually_exclusive_group(required=True)
    g.add_argument("--object", type=input_path, help=f"one object URDF {what} (a path, or relative to pybullet_data)")
    g.add_argument("--scene", type=input_path, help="a scene file (graspmix_cli scene; format graspmix.scene/1)")


COMMANDS = ("acquire", "execute")


def add_parsers(sub) -> None:
    s = sub.add_parser("acquire", help="a point cloud of an object or a scene as simulated depth cameras see it")
    _add_scene_source(s, "at its rest pose at the origin")
    s.add_argument(
        "--views",
        type=int_in(1, 64),
        default=1,
        help="1: one fixed camera above the table at 45 degrees, 640x480 (default); n > 1: the paper's ring of n",
    )
    s.add_argument("--noise", action="store_true", help="apply the depth noise model (sigma_p = 1 px, sigma_d = 1 mm)")
    s.add_argument("--seed", type=seed, default=0, help="seed of the noise")
    s.add_argument(
        "--keep",
        choices=["object", "scene"],
        default="scene",
        help="scene: what the camera sees, the table too (default); object: the objects' pixels only",
    )
    s.add_argument("--out", type=output_file, help="output cloud (.pcd); required unless --depth-out")
    s.add_argument(
        "--depth-out",
        type=png_file,
        help="also (or instead) write the one camera's depth image as a 16-bit PNG in millimetres, as a driver "
        "does, and print the --intrinsics and --camera-pose that go with it (--views 1)",
    )
    s.add_argument(
        "--encoding",
        choices=["binary", "binary_compressed", "ascii"],
        default="binary",
        help="PCD encoding (default binary; binary_compressed for files to keep)",
    )
    s.add_argument("--picture", type=picture_file, help="also save a picture of the depth images (.png)")
    s.add_argument(
        "--clean",
        action="store_true",
        help="clean up: voxel grid, outlier removal, and (with --keep scene) support-plane removal",
    )
    s.add_argument(
        "--voxel-size",
        type=float_in(0.0),
        help=f"m, voxel grid of --clean (default {FeatureScale.voxel_size})",
    )
    s.set_defaults(func=cmd_acquire)

    d = _core.SimSettings()  # the C++ defaults, for the help texts
    s = sub.add_parser("execute", help="execute a grasp from grasps.json on an object or in a scene in Bullet physics")
    _add_scene_source(s, "")
    s.add_argument("--object-pose", help="x,y,z,qx,qy,qz,qw of --object (default: its rest pose, as acquire puts it)")
    s.add_argument(
        "--closing",
        choices=["full", "learnt"],
        default="full",
        help="full: the fingers close until they stop, force-limited (default); learnt: just past the grasp joints",
    )
    s.add_argument("--out-scene", type=output_file, help="write the scene that remains (lifted objects removed)")
    s.add_argument("--grasps", type=input_path, required=True, help="grasps.json (format graspmix.grasps/1)")
    s.add_argument("--rank", type=int_in(1), default=1, help="which grasp (1 = the best)")
    s.add_argument(
        "--hand", type=urdf_path, help="hand URDF (default: the grasps file's hand, else the bundled WSG 50)"
    )
    s.add_argument("--grip-force", type=float_in(gt=0.0), help=f"N (default {d.grip_force:g})")
    s.add_argument("--lift-height", type=float_in(gt=0.0), help=f"m (default {d.lift_height:g})")
    s.add_argument(
        "--hold-time", type=float_in(0.0, MAX_SIM_TIME), help=f"s (default {d.hold_time:g}, at most {MAX_SIM_TIME:g})"
    )
    s.add_argument("--json", action="store_true", help="print the result as JSON")
    s.set_defaults(func=cmd_execute)
