"""Where a cloud was seen from, as the command line gives it: --viewpoint (repeatable), --camera-pose for a
cloud in a camera's frame, --plane for a known support; else the cloud file's own viewpoint(s). Or one camera's
depth image as its driver writes it: --depth with --intrinsics (and --depth-scale), posed by --camera-pose."""

from __future__ import annotations

import argparse

import numpy as np

from ..io import load_points
from ..perception import in_world
from .common import CliError, float_in, input_path, parse_floats


def add_view_arguments(parser: argparse.ArgumentParser) -> None:
    g = parser.add_argument_group("views")
    g.add_argument(
        "--viewpoint",
        action="append",
        metavar="X,Y,Z",
        help="a camera position (m, the cloud's frame); repeat for several cameras (each point is then taken "
        "as seen by the nearest); default: the cloud file's VIEWPOINT, else a camera at the origin",
    )
    g.add_argument(
        "--camera-pose",
        metavar="X,Y,Z,QX,QY,QZ,QW",
        help="the cloud is in a camera's frame with this pose in the world (unit quaternion): points and "
        "results are then in the world frame, and the camera is the viewpoint",
    )
    g.add_argument("--plane", metavar="A,B,C,D", help="a known support plane a x + b y + c z + d = 0 (world frame)")
    g.add_argument(
        "--depth",
        type=input_path,
        metavar="IMAGE",
        help="instead of --cloud: one camera's depth image, a 16-bit PNG in millimetres (as RealSense and ROS "
        "write it) or a .npy (H, W) array, with --intrinsics and the camera's --camera-pose",
    )
    g.add_argument("--intrinsics", metavar="FX,FY,CX,CY", help="the depth image's pinhole intrinsics (pixels)")
    g.add_argument(
        "--depth-scale",
        type=float_in(gt=0.0),
        metavar="M",
        help="metres per unit of the depth image (default: 0.001 for an integer image, 1 for a float one)",
    )


def _flag_viewpoints(texts: list[str], points: np.ndarray) -> np.ndarray:
    cams = np.array([parse_floats(t, 3, "--viewpoint") for t in texts])
    if len(cams) == 1:
        return cams[0]
    d = np.linalg.norm(points[:, None, :] - cams[None, :, :], axis=2)
    return cams[np.argmin(d, axis=1)]


def view_inputs(args, loaded_cloud) -> tuple[np.ndarray, np.ndarray | None, np.ndarray | None]:
    """(points, viewpoints, plane) from the flags of add_view_arguments and a cloud as
    graspmix.io.load_points returns it: (points, name, viewpoint (3,) or (N, 3) or None). Flags win over
    the file's viewpoints; --camera-pose maps the points (and the file's viewpoints) into the world."""
    points, _, file_viewpoints = loaded_cloud
    points = np.asarray(points, dtype=float)
    if args.viewpoint and args.camera_pose:
        raise CliError("--viewpoint and --camera-pose: give one (with --camera-pose the camera is the viewpoint)")
    viewpoints = None if file_viewpoints is None else np.asarray(file_viewpoints, dtype=float)
    if args.camera_pose:
        pose = parse_floats(args.camera_pose, 7, "--camera-pose")
        points, viewpoints = in_world(points, viewpoints, pose)  # ValueError: not a unit quaternion
    elif args.viewpoint:
        viewpoints = _flag_viewpoints(args.viewpoint, points)
    return points, viewpoints, known_plane(args)


def input_keywords(args, cloud_required: str) -> dict:
    """The input keywords of GraspModel.synthesize and perception.scene_input from the flags: --depth with its
    intrinsics, or --cloud as a path (its own viewpoints, organized or not) with --camera-pose, or, with --viewpoint,
    the cloud's points and the flags' viewpoints (view_inputs). CliError naming what is missing or does not go
    together; cloud_required says what --cloud is, for the message when neither is given."""
    image = depth_input(args)
    if image is not None:
        return image
    if not args.cloud:
        raise CliError(f"--cloud is required ({cloud_required}), or --depth with --intrinsics")
    if args.viewpoint:
        points, viewpoints, _ = view_inputs(args, load_points(args.cloud))
        return {"cloud": points, "viewpoints": viewpoints}
    return {
        "cloud": args.cloud,
        "camera_pose": parse_floats(args.camera_pose, 7, "--camera-pose") if args.camera_pose else None,
    }


def depth_input(args) -> dict | None:
    """The keywords of GraspModel.synthesize for --depth (depth, intrinsics, depth_scale, camera_pose), None without
    it; CliError for flags that do not go with it (or are missing)."""
    if args.depth is None:
        if args.intrinsics or args.depth_scale is not None:
            raise CliError("--intrinsics and --depth-scale go with --depth (a depth image)")
        return None
    if args.cloud:
        raise CliError("--cloud and --depth: give one (a cloud, or one camera's depth image)")
    if args.viewpoint:
        raise CliError("--viewpoint with --depth: the depth image's camera is its --camera-pose")
    if not args.intrinsics:
        raise CliError("--depth needs the camera's --intrinsics fx,fy,cx,cy (pixels)")
    return {
        "depth": args.depth,
        "intrinsics": parse_floats(args.intrinsics, 4, "--intrinsics"),
        "depth_scale": args.depth_scale,
        "camera_pose": parse_floats(args.camera_pose, 7, "--camera-pose") if args.camera_pose else None,
    }


def known_plane(args) -> np.ndarray | None:
    """--plane as [a, b, c, d], None without it."""
    if not args.plane:
        return None
    plane = parse_floats(args.plane, 4, "--plane")
    if np.linalg.norm(plane[:3]) == 0:
        raise CliError(f"--plane: (a, b, c) must not be zero, got {args.plane}")
    return plane
