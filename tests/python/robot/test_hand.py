"""Hand.from_urdf and fk against pybullet's own link frames, and the errors a user meets."""

from pathlib import Path

import graspmix
import numpy as np
import pybullet as pb
import pybullet_data
import pytest
from scipy.spatial.transform import Rotation

DATA = Path(pybullet_data.getDataPath())
WSG50 = graspmix.data_path("hands", "wsg50.urdf")
URDFS = {
    "wsg50": WSG50,
    "panda": DATA / "franka_panda" / "panda.urdf",
    "pr2_gripper": DATA / "pr2_gripper.urdf",
}


def random_pose(rng):
    return np.concatenate([rng.uniform(-1.0, 1.0, 3), Rotation.random(random_state=rng).as_quat()])


def random_configuration(hand, rng):
    lim = np.nan_to_num(hand.joint_limits, posinf=np.pi, neginf=-np.pi)
    return rng.uniform(lim[:, 0], lim[:, 1])


class Bullet:
    """A pybullet DIRECT session holding one URDF with a fixed base."""

    def __init__(self, urdf):
        self.client = pb.connect(pb.DIRECT)
        self.body = pb.loadURDF(str(urdf), useFixedBase=True, physicsClientId=self.client)
        n = pb.getNumJoints(self.body, physicsClientId=self.client)
        infos = [pb.getJointInfo(self.body, j, physicsClientId=self.client) for j in range(n)]
        self.joint_index = {i[1].decode(): i[0] for i in infos}
        self.link_index = {i[12].decode(): i[0] for i in infos}
        self.base_name = pb.getBodyInfo(self.body, physicsClientId=self.client)[0].decode()
        dyn = pb.getDynamicsInfo(self.body, -1, physicsClientId=self.client)
        self.base_inertial = np.concatenate([dyn[3], dyn[4]])  # T_link_inertial of the base

    def close(self):
        pb.disconnect(self.client)

    def link_poses(self, T_world_wrist, joint_values):
        """World link frames {name: (7,)}; the base is placed by its inertial frame, as pybullet wants."""
        T_world_com = graspmix.pose_multiply(T_world_wrist, self.base_inertial)
        pb.resetBasePositionAndOrientation(self.body, T_world_com[:3], T_world_com[3:], physicsClientId=self.client)
        for name, value in joint_values.items():
            pb.resetJointState(self.body, self.joint_index[name], value, physicsClientId=self.client)
        pos, orn = pb.getBasePositionAndOrientation(self.body, physicsClientId=self.client)
        # Remove the inertial offset: T_world_link = T_world_com * T_link_com^-1.
        out = {self.base_name: graspmix.pose_multiply(np.r_[pos, orn], graspmix.pose_inverse(self.base_inertial))}
        for name, j in self.link_index.items():
            s = pb.getLinkState(self.body, j, computeForwardKinematics=True, physicsClientId=self.client)
            out[name] = np.r_[s[4], s[5]]
        return out


def assert_poses_close(a, b, what):
    assert np.linalg.norm(a[:3] - b[:3]) < 1e-6, f"{what}: position {a[:3]} vs {b[:3]}"
    angle = (Rotation.from_quat(a[3:]).inv() * Rotation.from_quat(b[3:])).magnitude()
    assert angle < 1e-6, f"{what}: rotation differs by {angle} rad"


@pytest.mark.parametrize("name", sorted(URDFS))
def test_fk_matches_pybullet_link_frames(name):
    hand = graspmix.Hand.from_urdf(URDFS[name])
    sim = Bullet(URDFS[name])
    try:
        assert sim.base_name == hand.root_link
        assert set(sim.link_index) | {sim.base_name} == set(hand.link_names)
        rng = np.random.default_rng(11)
        wrists, configs = [], []
        for trial in range(40):
            T = random_pose(rng)
            q = random_configuration(hand, rng)
            wrists.append(T)
            configs.append(q)
            ours = hand.fk(T, q)
            # pybullet ignores <mimic>: it gets every movable joint's value, mimics resolved by graspmix.
            theirs = sim.link_poses(T, hand.all_joint_values(q))
            for i, link in enumerate(hand.link_names):
                assert_poses_close(ours[i], theirs[link], f"{name} trial {trial} link {link}")
        # The batched form gives the same poses.
        batch = hand.fk_batch(np.array(wrists), np.array(configs))
        assert batch.shape == (40, hand.n_links, 7)
        for i in range(40):
            np.testing.assert_allclose(batch[i], hand.fk(wrists[i], configs[i]), atol=1e-12)
    finally:
        sim.close()


def test_wsg50_model():
    hand = graspmix.Hand.from_urdf(WSG50)
    assert hand.joint_names == ["finger_left_joint"]
    np.testing.assert_allclose(hand.joint_limits, [[0.0, 0.055]])
    assert hand.link_names == ["palm", "finger_left", "finger_right"]
    assert hand.mimic_joints == {"finger_right_joint": ("finger_left_joint", 1.0, 0.0)}
    identity = np.array([0, 0, 0, 0, 0, 0, 1.0])
    # Opening = twice the joint value: the inner faces (link origins) are 2 q apart, facing each other.
    for q in (0.0, 0.02, 0.055):
        poses = hand.fk(identity, {"finger_left_joint": q})
        np.testing.assert_allclose(poses[1, :3], [-q, 0, 0.0725], atol=1e-12)
        np.testing.assert_allclose(poses[2, :3], [q, 0, 0.0725], atol=1e-12)
        x_left = Rotation.from_quat(poses[1, 3:]).apply([1, 0, 0])
        x_right = Rotation.from_quat(poses[2, 3:]).apply([1, 0, 0])
        np.testing.assert_allclose(x_left, [1, 0, 0], atol=1e-12)
        np.testing.assert_allclose(x_right, [-1, 0, 0], atol=1e-12)
    # Every link carries collision geometry (boxes), so every part that can touch an object is checked.
    for link in hand.link_names:
        shapes = hand.collision_shapes(link)
        assert shapes and all(s["type"] == "box" for s in shapes)
    verts, tris = hand.collision_mesh("finger_left")
    assert verts.shape[1] == 3 and tris.shape[1] == 3 and tris.max() < len(verts)
    # Closed, the fingers' inner faces meet at the centre plane; at 0.055 they are 110 mm apart.
    v = hand.collision_mesh("finger_left")[0]
    assert v[:, 0].max() == pytest.approx(0.0, abs=1e-12)


def test_wsg50_dimensions_match_pybullet_datas_wsg50_meshes():
    """The palm and finger boxes bound the meshes of pybullet_data's WSG 50 (new_free_base SDF)."""
    hand = graspmix.Hand.from_urdf(WSG50)
    meshes = DATA / "gripper" / "meshes"
    palm, _ = graspmix.load_mesh(meshes / "WSG50_110.stl")  # metres, in the palm frame
    palm_box = hand.collision_shapes("palm")[0]
    np.testing.assert_allclose(palm.min(0), palm_box["origin"][:3] - 0.5 * palm_box["size"], atol=2e-4)
    np.testing.assert_allclose(palm.max(0), palm_box["origin"][:3] + 0.5 * palm_box["size"], atol=2e-4)
    # The SDF's left jaw frame sits at x = -0.055 + s, z = 0.06, with the finger mesh (mm) 0.037 below it.
    # graspmix's joint value q (half the opening) corresponds to s = 0.052 - q.
    fmf, _ = graspmix.load_mesh(meshes / "WSG-FMF.stl", scale=[0.001] * 3)
    for q in (0.0, 0.03, 0.055):
        s = 0.052 - q
        sdf_finger = fmf + [-0.055 + s, 0.0, 0.06 - 0.037]
        pose = hand.fk(np.r_[0, 0, 0, 0, 0, 0, 1.0], [q])[hand.link_index("finger_left")]
        box = hand.collision_shapes("finger_left")[0]
        centre = pose[:3] + box["origin"][:3]  # finger_left is not rotated relative to the palm
        np.testing.assert_allclose(sdf_finger.min(0), centre - 0.5 * box["size"], atol=2e-4)
        np.testing.assert_allclose(sdf_finger.max(0), centre + 0.5 * box["size"], atol=2e-4)


def test_meshes_of_pybullet_hands_load_with_geometry():
    panda = graspmix.Hand.from_urdf(URDFS["panda"])
    finger = panda.collision_shapes("panda_leftfinger")[0]
    assert finger["type"] == "mesh" and finger["file"].endswith("finger.obj")
    assert finger["vertices"].shape[1] == 3 and len(finger["triangles"]) > 10
    pr2 = graspmix.Hand.from_urdf(URDFS["pr2_gripper"])
    tip = pr2.collision_shapes("left_gripper")[0]
    assert tip["file"].endswith("l_finger_collision.stl") and len(tip["triangles"]) > 10
    # Mesh extents agree with pybullet's AABB of the same link (same file, same frame).
    sim = Bullet(URDFS["pr2_gripper"])
    try:
        identity = np.array([0, 0, 0, 0, 0, 0, 1.0])
        q = np.zeros(pr2.n_dofs)
        sim.link_poses(identity, pr2.all_joint_values(q))
        lo, hi = pb.getAABB(sim.body, sim.link_index["left_gripper"], physicsClientId=sim.client)
        pose = pr2.fk(identity, q)[pr2.link_index("left_gripper")]
        v, _ = pr2.collision_mesh("left_gripper")
        world = Rotation.from_quat(pose[3:]).apply(v) + pose[:3]
        # pybullet pads AABBs by its collision margin (a few mm).
        np.testing.assert_allclose(world.min(0), lo, atol=0.01)
        np.testing.assert_allclose(world.max(0), hi, atol=0.01)
    finally:
        sim.close()


def test_joint_mappings():
    hand = graspmix.Hand.from_urdf(URDFS["panda"])
    q = random_configuration(hand, np.random.default_rng(0))
    as_dict = hand.joints_dict(q)
    assert list(as_dict) == sorted(hand.joint_names) or set(as_dict) == set(hand.joint_names)
    np.testing.assert_allclose(
        hand.fk(random_pose(np.random.default_rng(1)), as_dict), hand.fk(random_pose(np.random.default_rng(1)), q)
    )
    np.testing.assert_allclose(hand.joints_array(as_dict), q)
    assert "panda_finger_joint2" not in hand.joint_names  # a mimic joint
    # Batches accept a list of mappings and broadcast one configuration.
    wrists = np.tile([0, 0, 0, 0, 0, 0, 1.0], (3, 1))
    np.testing.assert_allclose(hand.fk_batch(wrists, [as_dict] * 3), hand.fk_batch(wrists, q))
    # ... and one wrist for many configurations.
    many = np.stack([q, hand.clamp(q + 0.1), hand.clamp(q - 0.1)])
    out = hand.fk_batch(wrists[0], many)
    assert out.shape == (3, hand.n_links, 7)
    np.testing.assert_allclose(out[1], hand.fk(wrists[0], many[1]), atol=1e-12)


def test_from_urdf_string_and_load_mesh_errors(tmp_path):
    hand = graspmix.Hand.from_urdf_string(WSG50.read_text())
    assert hand.link_names == ["palm", "finger_left", "finger_right"] and hand.source == "<string>"
    with pytest.raises(ValueError, match="gone.obj"):
        graspmix.load_mesh(tmp_path / "gone.obj")


def test_errors_name_the_input(tmp_path):
    missing = tmp_path / "nowhere.urdf"
    with pytest.raises(ValueError, match="nowhere.urdf"):
        graspmix.Hand.from_urdf(missing)
    empty = tmp_path / "empty.urdf"
    empty.write_text('<?xml version="1.0"?>\n<robot name="empty"></robot>\n')
    with pytest.raises(ValueError, match=r"empty\.urdf.*link"):
        graspmix.Hand.from_urdf(empty)
    hand = graspmix.Hand.from_urdf(WSG50)
    identity = [0, 0, 0, 0, 0, 0, 1]
    with pytest.raises(ValueError, match="'thumb'"):
        hand.fk(identity, {"finger_left_joint": 0.01, "thumb": 0.2})
    with pytest.raises(ValueError, match="'finger_left_joint' is missing"):
        hand.fk(identity, {})
    with pytest.raises(ValueError, match=r"joints: expected 1 joint values \(finger_left_joint\), got 2"):
        hand.fk(identity, [0.01, 0.02])
    with pytest.raises(ValueError, match="joints"):
        hand.fk_batch(np.tile(identity, (4, 1)), np.zeros((4, 3)))
    with pytest.raises(ValueError, match="T_world_wrist"):
        hand.fk([0, 0, 0], [0.01])
    with pytest.raises(ValueError, match="disagrees"):
        hand.fk(identity, {"finger_left_joint": 0.01, "finger_right_joint": 0.02})
    with pytest.raises(ValueError, match="link 'wrist'"):
        hand.collision_shapes("wrist")
