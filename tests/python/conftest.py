import numpy as np
import pytest


@pytest.fixture
def rng():
    return np.random.default_rng(12345)


BOX_URDF = """<?xml version="1.0"?>
<robot name="box"><link name="base">
  <visual><geometry><box size="{x} {y} {z}"/></geometry></visual>
  <collision><geometry><box size="{x} {y} {z}"/></geometry></collision>
  <inertial><mass value="0.2"/><inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial>
</link></robot>"""


@pytest.fixture(scope="session")
def box_urdf(tmp_path_factory):
    """A function (x, y, z) -> the path of a URDF of one box of that size (m), for pybullet to render."""

    def write(size):
        path = tmp_path_factory.mktemp("box") / "box.urdf"
        path.write_text(BOX_URDF.format(x=size[0], y=size[1], z=size[2]))
        return path

    return write
