"""The top-down baseline on synthetic box clouds: closing across the short side, centred, fingertips at the
stated height, the highest object of a scene, and a hand it cannot drive."""

import math
from dataclasses import dataclass

import numpy as np
import pytest
from graspmix.clutter.topdown import GRASP_DEPTH, TIP_MARGIN, plan_topdown, topdown_grasp
from graspmix.model.options import TABLE_CLEARANCE
from scipy.spatial.transform import Rotation

REACH = 0.0725 + 0.081  # flange to fingertips of the WSG 50 (data/hands/wsg50.urdf)


def box_surface(size, centre, yaw, n=3000, seed=0):
    """Points on the five visible faces of a box resting on z = 0, rotated by yaw about z."""
    rng = np.random.default_rng(seed)
    sx, sy, sz = size
    u = rng.uniform(-0.5, 0.5, (n, 3)) * size
    face = rng.integers(0, 5, n)
    u[face == 0, 2] = sz / 2  # top
    for k, (axis, sign) in enumerate([(0, 1), (0, -1), (1, 1), (1, -1)], start=1):
        u[face == k, axis] = sign * size[axis] / 2
    u[:, 2] += sz / 2
    R = Rotation.from_euler("z", yaw).as_matrix()
    return u @ R.T + np.array([*centre, 0.0])


@pytest.mark.parametrize("yaw", [0.0, 0.4, 1.3, -2.0])
def test_closes_across_the_short_side_centred(yaw):
    size = np.array([0.09, 0.035, 0.06])
    g = topdown_grasp(box_surface(size, (0.1, -0.05), yaw))
    R = Rotation.from_quat(g.T_world_wrist[3:]).as_matrix()
    short = Rotation.from_euler("z", yaw).apply([0.0, 1.0, 0.0])
    assert abs(R[:, 0] @ short) == pytest.approx(1.0, abs=1e-6)  # fingers travel along the wrist's x
    assert R[:, 2] == pytest.approx([0, 0, -1], abs=1e-9)  # approach straight down
    assert g.T_world_wrist[:2] == pytest.approx([0.1, -0.05], abs=2e-3)
    assert g.T_world_wrist[2] - REACH == pytest.approx(0.06 - GRASP_DEPTH, abs=1e-9)
    assert g.pregrasp_joints == {"finger_left_joint": 0.055} and g.grasp_joints == {"finger_left_joint": 0.0}


def test_a_flat_object_keeps_the_fingertips_above_the_table_clearance():
    # The table at z = 0.1 here and the points lifted with it: the tips at clearance + margin above it.
    pts = box_surface(np.array([0.06, 0.04, 0.02]), (0, 0), 0.0) + [0, 0, 0.1]
    g = topdown_grasp(pts, plane=[0, 0, 1, -0.1])
    assert g.T_world_wrist[2] - REACH == pytest.approx(0.1 + TABLE_CLEARANCE + TIP_MARGIN)


@dataclass
class Obj:
    index: int
    points: np.ndarray


@dataclass
class Scene:
    objects: list
    plane: object = None


def test_plan_picks_the_highest_object():
    low = Obj(0, box_surface(np.array([0.05, 0.05, 0.04]), (0.0, 0.0), 0.0))
    high = Obj(1, box_surface(np.array([0.05, 0.03, 0.09]), (0.12, 0.0), 0.3))
    grasp, index = plan_topdown(Scene([low, high]))
    assert index == 1 and grasp.object == 1
    assert grasp.T_world_wrist[:2] == pytest.approx([0.12, 0.0], abs=2e-3)
    with pytest.raises(ValueError, match="no object"):
        plan_topdown(Scene([]))


def test_a_hand_it_cannot_drive():
    from graspmix import _core

    urdf = """<robot name="pinch"><link name="base"><collision><geometry><box size="0.1 0.1 0.1"/></geometry>
    </collision></link><link name="f"><collision><geometry><box size="0.01 0.01 0.05"/></geometry></collision>
    </link><joint name="j" type="prismatic"><parent link="base"/><child link="f"/><axis xyz="1 0 0"/>
    <limit lower="0" upper="0.04" effort="10" velocity="1"/></joint></robot>"""
    hand = _core.Hand.from_urdf_string(urdf)
    with pytest.raises(ValueError, match="WSG 50 only"):
        topdown_grasp(box_surface(np.array([0.05, 0.03, 0.05]), (0, 0), 0.0), hand=hand)


def test_narrowest_axis_of_degenerate_clouds():
    from graspmix.clutter.topdown import narrowest_axis

    line = np.array([[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]])
    n, w = narrowest_axis(line)
    assert abs(n @ np.array([1, 1]) / math.sqrt(2)) == pytest.approx(0, abs=1e-9) and w == pytest.approx(0, abs=1e-9)
