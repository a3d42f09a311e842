"""Where a cloud was seen from, as the command line gives it: --viewpoint (repeatable), --camera-pose for a
cloud in a camera's frame, --plane for a known support; else the cloud file's own viewpoint(s)."""

from __future__ import annotations

import argparse

import numpy as np

from ..perception import in_world
from .common import CliError, parse_floats


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
    plane = None
    if args.plane:
        plane = parse_floats(args.plane, 4, "--plane")
        if np.linalg.norm(plane[:3]) == 0:
            raise CliError(f"--plane: (a, b, c) must not be zero, got {args.plane}")
    return points, viewpoints, plane
