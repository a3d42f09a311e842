"""Malformed hand and object URDFs for the command line, and what it must say about each.

CASES is a list of dicts:
  name:     a unique name of the case
  files:    {relative file name: bytes}, written into one folder
  argv:     graspmix_cli arguments; "{dir}" stands for that folder
  expect:   "error" (exit status 2 and one line on stderr) or "ok" (exit status 0)
  mentions: a substring that the error line must contain (the link, joint, setting or file at fault)

The cases are built deterministically (one seeded generator picks the links, joints and bad values), so
the corpus is the same on every run. Hands go through `demo --hand` (the hand is read before anything
else) and `execute --hand`; objects through `execute --object`, which reads them for the Bullet
simulation; simulation settings through `execute --hold-time` and friends.
"""

from __future__ import annotations

import json
import random

SEED = 11

# ---- a small parallel gripper and a box, with every number a case may break as a field ------------

HAND_FIELDS = {
    "palm_box": "0.14 0.05 0.06",
    "palm_origin": "0 0 0.03",
    "palm_mass": "1.0",
    "left_box": "0.02 0.03 0.07",
    "right_box": "0.02 0.03 0.07",
    "left_origin": "-0.01 0 0.035",
    "right_origin": "-0.01 0 0.035",
    "left_mass": "0.1",
    "right_mass": "0.1",
    "left_inertia": 'ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"',
    "left_extra": "",
    "right_extra": "",
    "left_joint_origin": "0 0 0.06",
    "right_joint_origin": "0 0 0.06",
    "left_axis": "-1 0 0",
    "right_axis": "-1 0 0",
    "left_limit": 'lower="0" upper="0.055" effort="40" velocity="0.2"',
    "right_limit": 'lower="0" upper="0.055" effort="40" velocity="0.2"',
    "left_type": "prismatic",
    "mimic": 'joint="finger_left_joint" multiplier="1" offset="0"',
    "extra": "",
}

HAND = """<?xml version="1.0"?>
<robot name="fuzzhand">
  <link name="palm">
    <inertial><origin xyz="{palm_origin}"/><mass value="{palm_mass}"/>
      <inertia ixx="1e-3" ixy="0" ixz="0" iyy="1e-3" iyz="0" izz="1e-3"/></inertial>
    <collision><origin xyz="{palm_origin}" rpy="0 0 0"/><geometry><box size="{palm_box}"/></geometry></collision>
  </link>
  <link name="finger_left">
    <inertial><mass value="{left_mass}"/><inertia {left_inertia}/></inertial>
    <collision><origin xyz="{left_origin}"/><geometry><box size="{left_box}"/></geometry></collision>{left_extra}
  </link>
  <link name="finger_right">
    <inertial><mass value="{right_mass}"/><inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial>
    <collision><origin xyz="{right_origin}"/><geometry><box size="{right_box}"/></geometry></collision>{right_extra}
  </link>
  <joint name="finger_left_joint" type="{left_type}">
    <parent link="palm"/><child link="finger_left"/>
    <origin xyz="{left_joint_origin}" rpy="0 0 0"/><axis xyz="{left_axis}"/><limit {left_limit}/>
  </joint>
  <joint name="finger_right_joint" type="prismatic">
    <parent link="palm"/><child link="finger_right"/>
    <origin xyz="{right_joint_origin}" rpy="0 0 3.141592653589793"/><axis xyz="{right_axis}"/><limit {right_limit}/>
    <mimic {mimic}/>
  </joint>{extra}
</robot>
"""

OBJECT_FIELDS = {
    "name": "box",
    "friction": '<lateral_friction value="1.0"/>',
    "mass": "0.3",
    "inertia": 'ixx="7e-4" ixy="0" ixz="0" iyy="6e-4" iyz="0" izz="3e-4"',
    "geometry": '<box size="0.06 0.10 0.14"/>',
    "origin": "0 0 0",
    "extra_link": "",
}

OBJECT = """<?xml version="1.0"?>
<robot name="{name}">
  <link name="box">
    <contact>{friction}</contact>
    <inertial><origin xyz="0 0 0"/><mass value="{mass}"/><inertia {inertia}/></inertial>
    <collision><origin xyz="{origin}" rpy="0 0 0"/><geometry>{geometry}</geometry></collision>
  </link>{extra_link}
</robot>
"""


def hand(**changes: str) -> bytes:
    unknown = set(changes) - set(HAND_FIELDS)
    assert not unknown, unknown
    return HAND.format(**{**HAND_FIELDS, **changes}).encode()


def box_object(**changes: str) -> bytes:
    unknown = set(changes) - set(OBJECT_FIELDS)
    assert not unknown, unknown
    return OBJECT.format(**{**OBJECT_FIELDS, **changes}).encode()


def grasps(hand_file: str) -> bytes:
    """A grasps.json with one top grasp of the gripper on the box."""
    doc = {
        "format": "graspmix.grasps/1",
        "hand": hand_file,
        "method": "gmm",
        "grasps": [
            {
                "rank": 1,
                "T_world_wrist": [0.0, 0.0, 0.30, 1.0, 0.0, 0.0, 0.0],
                "pregrasp_joints": {"finger_left_joint": 0.05},
                "grasp_joints": {"finger_left_joint": 0.02},
            }
        ],
    }
    return json.dumps(doc).encode()


def chain(n: int) -> bytes:
    """A hand of n links in one chain of revolute joints."""
    links = "".join(f'<link name="l{i}"/>\n' for i in range(n))
    joints = "".join(
        f'<joint name="j{i}" type="revolute"><parent link="l{i - 1}"/><child link="l{i}"/>'
        f'<origin xyz="0.001 0 0"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>\n'
        for i in range(1, n)
    )
    return f'<?xml version="1.0"?>\n<robot name="chain">\n{links}{joints}</robot>\n'.encode()


# ---- how a hand or an object reaches the command line ---------------------------------------------

DEMO = [
    "demo",
    "--hand",
    "{dir}/hand.urdf",
    "--wrist",
    "0,0,0.3,1,0,0,0",
    "--pregrasp",
    "finger_left_joint=0.05",
    "--close",
    "finger_left_joint=0.0",
    "--out",
    "{dir}/demo.json",
]
EXECUTE_HAND = ["execute", "--hand", "{dir}/hand.urdf", "--object", "{dir}/box.urdf", "--grasps", "{dir}/grasps.json"]
EXECUTE_OBJECT = ["execute", "--object", "{dir}/object.urdf", "--grasps", "{dir}/grasps.json"]

CASES: list[dict] = []


def _add(name: str, files: dict, argv: list, expect: str, mentions: str = "") -> None:
    assert name not in {c["name"] for c in CASES}, name
    CASES.append({"name": name, "files": files, "argv": list(argv), "expect": expect, "mentions": mentions})


def hand_case(name: str, text: bytes, mentions: str, via: str = "demo", expect: str = "error") -> None:
    """A hand file, read by `demo --hand` or `execute --hand` (with a good box and grasps)."""
    if via == "demo":
        _add(name, {"hand.urdf": text}, DEMO, expect, mentions)
    else:
        files = {"hand.urdf": text, "box.urdf": box_object(), "grasps.json": grasps("hand.urdf")}
        _add(name, files, EXECUTE_HAND, expect, mentions)


def object_case(
    name: str, text: bytes, mentions: str, expect: str = "error", extra_files: dict | None = None, argv_tail: tuple = ()
) -> None:
    """An object file, read by `execute --object` for a grasp of the bundled WSG 50."""
    files = {"object.urdf": text, "grasps.json": _wsg50_grasps(), **(extra_files or {})}
    _add(name, files, EXECUTE_OBJECT + list(argv_tail), expect, mentions)


def _wsg50_grasps() -> bytes:
    doc = json.loads(grasps("wsg50.urdf"))  # not beside the file: the bundled WSG 50
    return json.dumps(doc).encode()


def _build() -> None:
    rng = random.Random(SEED)
    good = hand()

    # -- structure: truncated, mismatched, wrong tags, empty, binary, deep --------------------------
    for k, cut in enumerate(sorted(rng.sample(range(40, len(good) - 12), 5))):
        hand_case(f"hand_truncated_{k}", good[:cut], "malformed XML", via="demo" if k % 2 else "execute")
    hand_case("hand_mismatched_end_tag", good.replace(b"</collision>", b"</colision>", 1), "</colision>")
    hand_case("hand_unclosed_comment", good.replace(b'<link name="palm">', b'<!-- <link name="palm">'), "comment")
    hand_case("hand_root_not_robot", good.replace(b"robot", b"robt"), "robot")
    hand_case("hand_empty_file", b"", "empty")
    hand_case("hand_binary_garbage", bytes(rng.getrandbits(8) for _ in range(512)), "hand.urdf")
    hand_case("hand_no_links", b'<?xml version="1.0"?><robot name="r"></robot>', "link")
    hand_case("hand_deep_nesting", b'<robot name="r"><link name="a">' + b"<x>" * 100000, "nested")
    hand_case("hand_chain_10000_links", chain(10000), "10000 links")
    hand_case("hand_chain_1001_links", chain(1001), "1001 links", via="execute")
    _add(
        "hand_missing_file",
        {"box.urdf": box_object(), "grasps.json": grasps("hand.urdf")},
        EXECUTE_HAND,
        "error",
        "hand.urdf",
    )
    _add("hand_is_a_folder", {"hand.urdf/readme.txt": b"a folder"}, DEMO, "error", "hand.urdf")

    # -- collision shapes -----------------------------------------------------------------------------
    bad_boxes = [
        "0.02 0.03",
        "a b c",
        "nan 0.03 0.07",
        "0.02 inf 0.07",
        "-0.02 0.03 0.07",
        "0 0.03 0.07",
        "1e300 0.03 0.07",
    ]
    for k, size in enumerate(bad_boxes):
        side = rng.choice(["left", "right"])
        hand_case(f"hand_box_{k}", hand(**{f"{side}_box": size}), f"finger_{side}", via=rng.choice(["demo", "execute"]))
    shapes = {
        "cylinder_negative": '<collision><geometry><cylinder radius="-0.01" length="0.05"/></geometry></collision>',
        "cylinder_text": '<collision><geometry><cylinder radius="r" length="0.05"/></geometry></collision>',
        "sphere_zero": '<collision><geometry><sphere radius="0"/></geometry></collision>',
        "unknown_shape": '<collision><geometry><capsule radius="0.01" length="0.05"/></geometry></collision>',
        "empty_geometry": "<collision><geometry></geometry></collision>",
        "bad_visual": '<visual><geometry><box size="1 1"/></geometry></visual>',
        "far_origin": '<collision><origin xyz="1e6 0 0"/><geometry><sphere radius="0.01"/></geometry></collision>',
        "nan_origin": '<collision><origin xyz="nan 0 0"/><geometry><sphere radius="0.01"/></geometry></collision>',
        "mesh_missing": '<collision><geometry><mesh filename="gone.stl"/></geometry></collision>',
    }
    for k, (what, xml) in enumerate(shapes.items()):
        side = ["left", "right"][k % 2]
        mention = "gone.stl" if what == "mesh_missing" else f"finger_{side}"
        hand_case(f"hand_{what}", hand(**{f"{side}_extra": xml}), mention, via=["demo", "execute"][k % 3 == 0])
    for k, scale in enumerate(["0 1 1", "nan 1 1", "1e300 1 1"]):
        xml = f'<collision><geometry><mesh filename="part.obj" scale="{scale}"/></geometry></collision>'
        _add(
            f"hand_mesh_scale_{k}",
            {"hand.urdf": hand(left_extra=xml), "part.obj": _cube_obj()},
            DEMO,
            "error",
            "finger_left",
        )
    garbage = bytes(rng.getrandbits(8) for _ in range(256))
    xml = '<collision><geometry><mesh filename="part.stl"/></geometry></collision>'
    _add("hand_mesh_garbage", {"hand.urdf": hand(right_extra=xml), "part.stl": garbage}, DEMO, "error", "part.stl")
    _add(
        "hand_mesh_huge_vertex",
        {
            "hand.urdf": hand(right_extra=xml.replace(".stl", ".obj")),
            "part.obj": _cube_obj().replace(b"v 0.5 0.5 0.5", b"v 1e300 0.5 0.5"),
        },
        DEMO,
        "error",
        "part.obj",
    )

    # -- joints ---------------------------------------------------------------------------------------
    joint_cases = {
        "lower_above_upper": ("left_limit", 'lower="0.055" upper="0" effort="40" velocity="0.2"', "finger_left_joint"),
        "lower_above_upper_mimic": (
            "right_limit",
            'lower="1" upper="-1" effort="40" velocity="0.2"',
            "finger_right_joint",
        ),
        "limit_nan": ("left_limit", 'lower="nan" upper="0.055" effort="40" velocity="0.2"', "lower"),
        "limit_inf": ("left_limit", 'lower="0" upper="inf" effort="40" velocity="0.2"', "upper"),
        "zero_axis": ("left_axis", "0 0 0", "finger_left_joint"),
        "nan_axis": ("right_axis", "nan 0 1", "finger_right_joint"),
        "nan_origin": ("left_joint_origin", "0 nan 0.06", "finger_left_joint"),
        "huge_origin": ("right_joint_origin", "0 0 1e300", "finger_right_joint"),
        "type_ball": ("left_type", "ball", "ball"),
        "type_floating": ("left_type", "floating", "finger_left_joint"),
        "mimic_unknown": ("mimic", 'joint="thumb" multiplier="1" offset="0"', "thumb"),
        "mimic_nan": ("mimic", 'joint="finger_left_joint" multiplier="nan" offset="0"', "multiplier"),
        "mimic_text": ("mimic", 'joint="finger_left_joint" multiplier="1" offset="x"', "offset"),
        "mimic_itself": ("mimic", 'joint="finger_right_joint" multiplier="1" offset="0"', "finger_right_joint"),
    }
    for k, (what, (field, value, mention)) in enumerate(joint_cases.items()):
        hand_case(f"hand_joint_{what}", hand(**{field: value}), mention, via=["demo", "execute"][k % 2])
    no_limit = hand().replace(
        b'<limit lower="0" upper="0.055" effort="40" velocity="0.2"/>\n  </joint>\n  <joint name="finger_right_joint"',
        b'\n  </joint>\n  <joint name="finger_right_joint"',
    )
    assert no_limit != hand()
    hand_case("hand_joint_limit_missing", no_limit, "finger_left_joint")
    tree_cases = {
        "parent_missing": (
            '<joint name="extra" type="fixed"><parent link="ghost"/><child link="tip"/></joint><link name="tip"/>',
            "ghost",
        ),
        "two_roots": ('<link name="loose"/>', "root"),
        "duplicate_link": ('<link name="palm"/>', "palm"),
        "duplicate_joint": (
            '<link name="tip"/><joint name="finger_left_joint" type="fixed"><parent link="palm"/>'
            '<child link="tip"/></joint>',
            "finger_left_joint",
        ),
        "link_without_name": ("<link/>", "name"),
        "cycle": ('<joint name="back" type="fixed"><parent link="finger_left"/><child link="palm"/></joint>', "root"),
    }
    for what, (xml, mention) in tree_cases.items():
        hand_case(f"hand_tree_{what}", hand(extra=xml), mention)

    # -- inertial ---------------------------------------------------------------------------------------
    for k, (field, value, mention) in enumerate(
        [
            ("left_mass", "-0.1", "finger_left"),
            ("right_mass", "nan", "finger_right"),
            ("palm_mass", "1e999", "palm"),
            ("left_inertia", 'ixx="a" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"', "finger_left"),
        ]
    ):
        hand_case(f"hand_inertial_{k}", hand(**{field: value}), mention, via=["execute", "demo"][k % 2])

    # -- objects ----------------------------------------------------------------------------------------
    object_cases = {
        "mass_zero": ({"mass": "0"}, "mass"),
        "mass_negative": ({"mass": "-0.3"}, "mass"),
        "mass_nan": ({"mass": "nan"}, "mass"),
        "box_two_numbers": ({"geometry": '<box size="0.06 0.10"/>'}, "box"),
        "box_negative": ({"geometry": '<box size="0.06 -0.10 0.14"/>'}, "box"),
        "box_huge": ({"geometry": '<box size="0.06 1e300 0.14"/>'}, "box"),
        "mesh_missing": ({"geometry": '<mesh filename="gone.obj"/>'}, "gone.obj"),
        "mesh_scale_zero": ({"geometry": '<mesh filename="part.obj" scale="0 0 0"/>'}, "mesh scale"),
        "no_geometry": ({"geometry": ""}, "box"),
        "origin_nan": ({"origin": "0 0 nan"}, "box"),
        "friction_nan": ({"friction": '<lateral_friction value="nan"/>'}, "lateral_friction"),
        "friction_negative": ({"friction": '<lateral_friction value="-1"/>'}, "lateral_friction"),
        "friction_text": ({"friction": '<lateral_friction value="0.5abc"/>'}, "lateral_friction"),
        "inertia_scaling_zero": ({"friction": '<inertia_scaling value="0"/>'}, "inertia_scaling"),
        "two_links": (
            {
                "extra_link": '<link name="lid"/><joint name="hinge" type="fixed"><parent link="box"/>'
                '<child link="lid"/></joint>'
            },
            "one link",
        ),
    }
    for what, (changes, mention) in object_cases.items():
        object_case(f"object_{what}", box_object(**changes), mention, extra_files={"part.obj": _cube_obj()})
    text = box_object()
    for k, cut in enumerate(sorted(rng.sample(range(30, len(text) - 12), 2))):
        object_case(f"object_truncated_{k}", text[:cut], "malformed XML")
    object_case("object_empty", b"", "empty")
    object_case("object_chain_10000_links", chain(10000), "10000 links")
    _add("object_missing_file", {"grasps.json": _wsg50_grasps()}, EXECUTE_OBJECT, "error", "object.urdf")

    # -- simulation settings ------------------------------------------------------------------------------
    for k, (flag, value, mention) in enumerate(
        [
            ("--hold-time", "1e7", "hold-time"),
            ("--hold-time", "nan", "hold-time"),
            ("--grip-force", "inf", "grip-force"),
            ("--grip-force", "0", "grip-force"),
            ("--lift-height", "1e9", "lift_height"),
        ]
    ):
        object_case(f"settings_{k}_{flag[2:]}", box_object(), mention, argv_tail=(flag, value))

    # -- valid files that must keep working ---------------------------------------------------------------
    hand_case("ok_hand", good, "", via="execute", expect="ok")
    hand_case(
        "ok_hand_crlf_and_comments",
        good.replace(b"\n", b"\r\n").replace(b"<link", b"<!-- a > b --><link"),
        "",
        via="execute",
        expect="ok",
    )
    hand_case("ok_hand_massless_link", hand(left_mass="0"), "", via="execute", expect="ok")
    hand_case("ok_hand_limit_defaults", hand(left_limit='effort="40" velocity="0.2"'), "", via="execute", expect="ok")
    object_case("ok_object", box_object(), "", expect="ok")
    object_case(
        "ok_object_mesh",
        box_object(geometry='<mesh filename="part.obj" scale="0.05 0.05 0.1"/>'),
        "",
        expect="ok",
        extra_files={"part.obj": _cube_obj()},
    )


def _cube_obj() -> bytes:
    """A unit cube centred at the origin as an OBJ file."""
    v = [f"v {x} {y} {z}" for x in (-0.5, 0.5) for y in (-0.5, 0.5) for z in (-0.5, 0.5)]
    faces = [
        (1, 3, 2),
        (2, 3, 4),
        (5, 6, 7),
        (6, 8, 7),
        (1, 2, 5),
        (2, 6, 5),
        (3, 7, 4),
        (4, 7, 8),
        (1, 5, 3),
        (3, 5, 7),
        (2, 4, 6),
        (4, 8, 6),
    ]
    return ("\n".join(v + [f"f {a} {b} {c}" for a, b, c in faces]) + "\n").encode()


_build()
