"""What a hand is, read from its URDF: links, joints, mimic relations, the wrist frame, the approach axis,
each joint's closing direction and its opening at the joint limits: a two-finger gripper's width, or the
diameter that three or more fingers around the approach axis leave free (describe_hand; `graspmix_cli
hand`). Everything is derived by forward kinematics of the collision geometry, so it holds for any hand
graspmix can load."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np

from .. import _core
from ..io.checks import check_input_file, check_output_path, check_path_text

FINGERS_AGREE_DEG = 30.0  # the fingers' direction within this angle of the hand's approach axis agrees with it
CONTINUOUS_SPAN = 0.5  # rad either side of 0 to probe a continuous joint
SPREAD_TOLERANCE = 1e-6  # m: a joint whose limits change its fingertips' spread less neither opens nor closes


def _limits(hand) -> np.ndarray:
    """(n_dofs, 2) the limits, a continuous joint probed at -+CONTINUOUS_SPAN."""
    lim = np.array(hand.joint_limits, dtype=float).reshape(-1, 2)
    lim[~np.isfinite(lim[:, 0]), 0] = -CONTINUOUS_SPAN
    lim[~np.isfinite(lim[:, 1]), 1] = CONTINUOUS_SPAN
    return lim


def _moving(hand) -> dict:
    """link -> set of independent joints that move it (through its chain of joints to the wrist)."""
    joints = {j["child"]: j for j in hand.joints}
    mimic = hand.mimic_joints
    out = {}
    for link in hand.link_names:
        dofs, name = set(), link
        while name in joints:
            j = joints[name]
            if j["type"] != "fixed":
                dofs.add(mimic[j["name"]][0] if j["name"] in mimic else j["name"])
            name = j["parent"]
        out[link] = dofs
    return out


def _vertices(hand, meshes: dict, q: np.ndarray, links) -> dict:
    """link -> its collision vertices (V, 3) in the wrist frame at configuration q."""
    poses = hand.fk(np.array([0, 0, 0, 0, 0, 0, 1.0]), q)
    out = {}
    for i, name in enumerate(hand.link_names):
        if name in links and len(meshes[name]):
            out[name] = _transform(poses[i], meshes[name])
    return out


def _transform(pose: np.ndarray, points: np.ndarray) -> np.ndarray:
    from scipy.spatial.transform import Rotation

    return Rotation.from_quat(pose[3:]).apply(points) + pose[:3]


def _unit(v) -> np.ndarray:
    v = np.asarray(v, dtype=float)
    n = np.linalg.norm(v)
    return v / n if n > 1e-12 else np.zeros(3)


def _spread(points: np.ndarray, centre: np.ndarray, axis: np.ndarray) -> float:
    """Mean distance of points from the line through centre along axis."""
    d = points - centre
    return float(np.linalg.norm(d - np.outer(d @ axis, axis), axis=1).mean())


def _closing(hand, meshes, moving, tips, mid, lim, centre, axis) -> dict:
    """independent joint -> +1 when increasing it closes the fingers it moves (their tips come nearer the
    approach line), -1 when decreasing it does, 0 when it moves no fingertip or neither opens nor closes."""
    out = {}
    for k, name in enumerate(hand.joint_names):
        links = [t for t in tips if name in moving[t]]
        if not links:
            out[name] = 0
            continue
        spread = []
        for value in lim[k]:
            q = mid.copy()
            q[k] = value
            spread.append(_spread(np.vstack(list(_vertices(hand, meshes, q, links).values())), centre, axis))
        change = spread[1] - spread[0]
        out[name] = 0 if abs(change) < SPREAD_TOLERANCE else (1 if change < 0 else -1)
    return out


def _sides(tip_vertices: dict, centre: np.ndarray, axis: np.ndarray):
    """The fingertips split in two by their offsets across the approach axis: (side a, side b, unit
    direction from a to b), or None when they do not fall into two sides."""
    names = list(tip_vertices)
    if len(names) < 2:
        return None
    offsets = np.array([tip_vertices[n].mean(axis=0) - centre for n in names])
    offsets -= np.outer(offsets @ axis, axis)
    _, s, vt = np.linalg.svd(offsets, full_matrices=False)
    d = vt[0]
    side = offsets @ d
    a = [n for n, v in zip(names, side) if v < 0]
    b = [n for n, v in zip(names, side) if v >= 0]
    if not a or not b or (len(s) > 1 and s[1] > 0.5 * s[0]):  # not a two-sided arrangement
        return None
    return a, b, d


def _width(hand, meshes, q, side_a, side_b, d, axis) -> float:
    """The gap between the two sides' fingertip links (the one reaching farthest along the approach on
    each side) measured along d: negative when they overlap."""
    verts = _vertices(hand, meshes, q, set(side_a) | set(side_b))

    def tip(side):
        return max(side, key=lambda n: float((verts[n] @ axis).max()))

    return round(float((verts[tip(side_b)] @ d).min() - (verts[tip(side_a)] @ d).max()), 9)


def _clear_diameter(hand, meshes, q, tips, centre, axis) -> float:
    """Diameter of the widest circle about the line through centre along axis that the fingertip links leave
    free: twice the least distance from the line to a link's collision geometry (its convex hull, seen along the
    axis), 0 where a link reaches across the line. A centric hand's opening (three or more fingers around it)."""
    from scipy.spatial import ConvexHull, QhullError

    u = _unit(np.cross(axis, [1.0, 0.0, 0.0] if abs(axis[0]) < 0.9 else [0.0, 1.0, 0.0]))
    v = np.cross(axis, u)
    radius = np.inf
    for pts in _vertices(hand, meshes, q, set(tips)).values():
        flat = (pts - centre) @ np.column_stack([u, v])  # (V, 2) across the axis, the line at the origin
        try:
            hull = ConvexHull(flat)
        except QhullError:  # flat seen edge-on: its points are the nearest guess
            radius = min(radius, float(np.linalg.norm(flat, axis=1).min()))
            continue
        if np.all(hull.equations[:, 2] <= 0.0):  # the line passes through the link
            return 0.0
        ring = flat[hull.vertices]
        a, b = ring, np.roll(ring, -1, axis=0)
        t = np.clip(np.einsum("ij,ij->i", -a, b - a) / np.einsum("ij,ij->i", b - a, b - a), 0.0, 1.0)
        radius = min(radius, float(np.linalg.norm(a + t[:, None] * (b - a), axis=1).min()))
    return round(2.0 * radius, 9)


def describe_hand(path: str | Path, hand=None) -> dict:
    """A hand's description from its URDF (see the module's docstring). ValueError for a file that is
    missing or not a URDF graspmix can load. hand: the loaded graspmix.Hand, to skip reading it again.

    Keys: urdf, name, wrist (the root link, the frame of T_world_wrist), links, joints (type, parent,
    child, axis in the child frame, limits, mimic, independent, closing), independent_joints, mimic,
    approach_axis (the hand's axis, where it came from, the fingers' direction from the wrist and the angle
    between them), fingertips (Hand.fingertips),
    closing (independent joint -> +1/-1), fingers (two sides of fingertip links, or None), opening_width
    (m at the lower and upper limits, two-finger grippers only, else None), opening_diameter (m at the lower
    and upper limits, hands of three or more fingertips around the approach axis only, else None: the widest
    circle about the axis through the fingertips' centre that they leave free)."""
    path = check_input_file(check_path_text(path, "urdf"), "urdf")
    hand = hand or _core.Hand.from_urdf(str(path))
    moving = _moving(hand)
    tips = list(hand.fingertips)  # given by the URDF's <graspmix> element or inferred (Hand.fingertips)
    meshes = {name: np.asarray(hand.collision_mesh(name)[0]) for name in hand.link_names}
    lim = _limits(hand)
    mid = lim.mean(axis=1)
    tip_vertices = _vertices(hand, meshes, mid, set(tips))
    pts = np.vstack(list(tip_vertices.values())) if tip_vertices else np.zeros((0, 3))
    approach = np.asarray(hand.approach_axis, dtype=float)
    fingers_dir = _unit(pts.mean(axis=0)) if len(pts) else np.zeros(3)
    angle = float(np.degrees(np.arccos(np.clip(fingers_dir @ approach, -1, 1)))) if len(pts) else None
    axis = approach
    centre = pts.mean(axis=0) if len(pts) else np.zeros(3)
    closing = _closing(hand, meshes, moving, tips, mid, lim, centre, axis)
    sides = _sides(tip_vertices, centre, axis)
    width = None
    if sides is not None:
        width = {
            limit: _width(hand, meshes, lim[:, i], sides[0], sides[1], sides[2], axis)
            for i, limit in enumerate(("lower", "upper"))
        }
    diameter = None
    if sides is None and len(tip_vertices) >= 3:
        diameter = {
            limit: _clear_diameter(hand, meshes, lim[:, i], tips, centre, axis)
            for i, limit in enumerate(("lower", "upper"))
        }
    return {
        "urdf": str(path),
        "name": hand.name,
        "wrist": hand.root_link,
        "links": [_link(hand, name, moving[name], name in tips) for name in hand.link_names],
        "joints": [_joint(j, hand, closing) for j in hand.joints],
        "independent_joints": list(hand.joint_names),
        "mimic": {k: {"joint": m, "multiplier": a, "offset": b} for k, (m, a, b) in hand.mimic_joints.items()},
        "approach_axis": {
            "axis": [float(v) + 0.0 for v in approach],
            "source": hand.grasp_axes_source,
            "snap_deg": _core.HandLoadSettings().approach_snap_deg,
            "fingers_direction": [round(float(v), 9) + 0.0 for v in fingers_dir],
            "angle_deg": angle,
            "agrees": angle is not None and angle <= FINGERS_AGREE_DEG,
        },
        "fingertips": tips,
        "closing": closing,
        "fingers": None if sides is None else [sides[0], sides[1]],
        "opening_width": width,
        "opening_diameter": diameter,
    }


def _link(hand, name: str, dofs: set, tip: bool) -> dict:
    return {
        "name": name,
        "shapes": [s["type"] for s in hand.collision_shapes(name)],
        "moved_by": sorted(dofs),
        "fingertip": tip,
    }


def _joint(j: dict, hand, closing: dict) -> dict:
    lower, upper = (float(v) for v in j["limits"])
    independent = j["type"] != "fixed" and j["mimic"] is None
    out = {
        "name": j["name"],
        "type": j["type"],
        "parent": j["parent"],
        "child": j["child"],
        "axis": [float(v) for v in j["axis"]],
        "lower": lower if j["type"] != "fixed" and np.isfinite(lower) else None,  # None: fixed or unbounded
        "upper": upper if j["type"] != "fixed" and np.isfinite(upper) else None,
        "mimic": j["mimic"],
        "independent": independent,
        "closing": None,
    }
    if independent:
        out["closing"] = closing[j["name"]]
    elif j["mimic"] is not None:
        master, multiplier, _ = hand.mimic_joints[j["name"]]
        out["closing"] = int(np.sign(multiplier)) * closing[master]
    return out


def hand_urdf_from_robot(robot_urdf: str | Path, wrist_link: str, out: str | Path, name: str | None = None) -> Path:
    """Writes a hand-only URDF cut from a robot's URDF: the link `wrist_link` becomes the root (the wrist
    frame) and every link and joint below it is kept (mimic joints, limits and collision shapes as they
    are); the links above it, transmissions and simulator tags are dropped. Mesh file names are written as
    absolute paths (package://pkg/... looked up in the robot URDF's folder and its parents, as Hand.from_urdf
    does), so `out` loads wherever it is moved while the robot's meshes stay where they are. Returns `out`;
    ValueError for an unknown link or a mesh that is not found."""
    robot_urdf = check_input_file(check_path_text(robot_urdf, "robot urdf"), "robot urdf")
    out = Path(check_path_text(out, "out"))
    try:
        root = ET.parse(robot_urdf).getroot()
    except ET.ParseError as e:
        raise ValueError(f"{robot_urdf}: malformed XML: {e}") from None
    links = {e.get("name"): e for e in root.findall("link")}
    if wrist_link not in links:
        raise ValueError(f"{robot_urdf}: no link named {wrist_link!r} (links: {', '.join(sorted(links))[:200]})")
    joints = root.findall("joint")
    keep, frontier = {wrist_link}, [wrist_link]
    kept_joints = []
    while frontier:
        parent = frontier.pop()
        for j in joints:
            if j.find("parent") is not None and j.find("parent").get("link") == parent:
                kept_joints.append(j)
                child = j.find("child").get("link")
                keep.add(child)
                frontier.append(child)
    hand = ET.Element("robot", {"name": name or f"{root.get('name', 'robot')}_{wrist_link}"})
    for link_name in (n for n in links if n in keep):
        hand.append(links[link_name])
    hand.extend(kept_joints)
    base = robot_urdf.resolve().parent
    for mesh in hand.iter("mesh"):
        mesh.set("filename", str(_mesh_file(mesh.get("filename"), base)))
    ET.indent(hand)
    check_output_path(out, "out")
    out.write_text(ET.tostring(hand, encoding="unicode") + "\n")
    return out


def write_hand_axes(urdf: str | Path, out: str | Path, approach_axis=None, fingertips=None) -> Path:
    """Writes `urdf` to `out` (mesh paths made absolute, as hand_urdf_from_robot does) with its grasp
    axes given in its <graspmix> element: approach_axis (3,) in the wrist frame and/or fingertips (link names);
    None keeps what the file gives (or the inference). The hand is read back to check them: ValueError naming a
    bad axis or link. Returns `out`."""
    urdf = check_input_file(check_path_text(urdf, "urdf"), "urdf")
    hand = _core.Hand.from_urdf(str(urdf))
    given = ET.parse(urdf).getroot().find(_core.URDF_AXES_ELEMENT)
    attrs = dict(given.attrib) if given is not None else {}
    if approach_axis is not None:
        a = np.asarray(approach_axis, dtype=float)
        if a.shape != (3,) or not np.all(np.isfinite(a)) or not np.linalg.norm(a) > 0:
            raise ValueError(f"approach axis: expected 3 finite numbers, not all zero, got {approach_axis!r}")
        attrs["approach_axis"] = " ".join(f"{v:.9g}" for v in a / np.linalg.norm(a))
    if fingertips is not None:
        unknown = [n for n in fingertips if n not in hand.link_names]
        if not fingertips or unknown:
            raise ValueError(f"fingertips: {', '.join(unknown) or 'none given'} (links: {', '.join(hand.link_names)})")
        attrs["fingertips"] = " ".join(fingertips)
    out = hand_urdf_from_robot(urdf, hand.root_link, out, name=hand.name)
    root = ET.parse(out).getroot()
    if attrs:
        root.append(ET.Element(_core.URDF_AXES_ELEMENT, attrs))
    ET.indent(root)
    out.write_text(ET.tostring(root, encoding="unicode") + "\n")
    _core.Hand.from_urdf(str(out))  # the axes checked as every reader will
    return out


def _mesh_file(filename: str, base: Path) -> Path:
    """A URDF's mesh file name as a file: file:// stripped, absolute, relative to base, or package://pkg/rest
    as <dir>/pkg/rest or <dir>/rest for base and each of its parents (Hand.from_urdf's order)."""
    name = filename.removeprefix("file://")
    tries = [Path(name)] if Path(name).is_absolute() else [base / name]
    if name.startswith("package://"):
        pkg, _, rest = name[len("package://") :].partition("/")
        tries = [base / rest] + [d / p for d in (base, *base.parents) for p in (Path(pkg) / rest, Path(rest))]
    for t in tries:
        if t.is_file():
            return t.resolve()
    raise ValueError(f"mesh {filename!r}: not found (tried {', '.join(map(str, tries[:4]))}, ...)")
