"""Hands of pybullet_data, and the bundled three-finger hand, made into graspmix models the way a new user would
(issue 27's trial).

    python scripts/hand_models.py OUT_DIR [--hands panda,xarm,pr2,three_finger] [--method gmm] [--seed 0]

For each hand, with the project's own command line only (a subprocess per step, so this is the recipe a user
types): `graspmix_cli hand --urdf ROBOT --wrist-link LINK --out OUT_DIR/NAME/hand.urdf` cuts the hand from its
robot (the PR2 gripper and the bundled data/hands/three_finger.urdf are used as shipped), `graspmix_cli demo`
records one top-down demonstration of the bundled box (60 x 100 x 140 mm standing on the table; the fingers close across its 60 mm side, about 4-5 cm below its
top) and `graspmix_cli learn` fits a model. Written under OUT_DIR/NAME/: hand.urdf (cut hands), demo.json,
demo.pcd, demo.png, model.json. The WSG 50's model is the bundled data/models/box_wsg50_gmm.json, made the
same way (data/demos/box_wsg50.json). A step that fails stops the script with its command and message.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

import pybullet_data
from graspmix.io import resolve_path

PYBULLET_DATA = Path(pybullet_data.getDataPath())
# The wrist turned so that its +z (the approach) points down and its y, along which these fingers close, along
# the world's x (the box's 60 mm side): x -> y, y -> x, z -> -z.
DOWN_Y_ACROSS = "0.7071068,0.7071068,0,0"


@dataclass(frozen=True)
class HandRecipe:
    name: str
    robot: str  # relative to pybullet_data, or package://graspmix/... (the bundled data)
    wrist_link: str | None  # None: the URDF is a hand already (used as shipped)
    wrist: str  # x,y,z,qx,qy,qz,qw of the wrist over the box (its top at z = 0.14 m)
    pregrasp: str
    close: str


HANDS = {
    # Palm's lowest point 66 mm below the wrist, fingertips 112 mm: the tips 36 mm below the box's top.
    "panda": HandRecipe(
        "panda",
        "franka_panda/panda.urdf",
        "panda_hand",
        f"0,0,0.216,{DOWN_Y_ACROSS}",
        "panda_finger_joint1=0.04",
        "panda_finger_joint1=0",
    ),
    # Base link's lowest point 103 mm below the wrist, fingertips 162 mm: the tips 49 mm below the top.
    "xarm": HandRecipe(
        "xarm",
        "xarm/xarm6_with_gripper.urdf",
        "xarm_gripper_base_link",
        f"0,0,0.253,{DOWN_Y_ACROSS}",
        "drive_joint=0",
        "drive_joint=0.85",
    ),
    # As shipped: the fingers along the wrist's +x (310 mm out), closing along its y. The wrist's x turned
    # down and its y along the world's x: the tips 30 mm below the top.
    "pr2": HandRecipe(
        "pr2",
        "pr2_gripper.urdf",
        None,
        "0,0,0.42,0.5,0.5,-0.5,0.5",
        "left_gripper_joint=0.5,right_gripper_joint=0.5",
        "left_gripper_joint=0,right_gripper_joint=0",
    ),
    # Bundled: finger_1 on the wrist's +x, turned to the world's +y onto the box's narrow face (60 mm wide);
    # finger_2 and finger_3 (120 degrees on) close with their inner edges on its broad faces, 60 mm apart. A centric hand
    # stops when all three touch: the wrist 10 mm off the box's centre along +y makes them touch together
    # (finger_1_joint about 0.040, the inner faces 40 mm from the axis). Fingertips 158 mm below the wrist: the
    # tips 40 mm below the top, the jaws 40 mm above it.
    "three_finger": HandRecipe(
        "three_finger",
        "package://graspmix/hands/three_finger.urdf",
        None,
        f"0,0.01,0.258,{DOWN_Y_ACROSS}",
        "finger_1_joint=0.065",
        "finger_1_joint=0.008",
    ),
}


def run(args: list[str]) -> None:
    cmd = [sys.executable, "-m", "graspmix.cli", *args]
    print("$ graspmix_cli " + " ".join(args), flush=True)
    done = subprocess.run(cmd, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"failed ({done.returncode}): graspmix_cli {' '.join(args)}\n{done.stderr.strip()}")
    for line in done.stdout.strip().splitlines()[-3:]:
        print("  " + line)


def hand_urdf(recipe: HandRecipe, folder: Path) -> Path:
    """The hand's URDF: cut from its robot into folder/hand.urdf, or the file itself (pybullet_data's, bundled)."""
    if recipe.wrist_link is None:
        return resolve_path(recipe.robot, PYBULLET_DATA)
    out = folder / "hand.urdf"
    robot = resolve_path(recipe.robot, PYBULLET_DATA)
    run(["hand", "--urdf", str(robot), "--wrist-link", recipe.wrist_link, "--out", str(out)])
    return out


def make(recipe: HandRecipe, out_dir: Path, method: str, seed: int) -> Path:
    """hand -> demo -> learn for one hand; returns its model file."""
    folder = out_dir / recipe.name
    folder.mkdir(parents=True, exist_ok=True)
    hand = hand_urdf(recipe, folder)
    demo = folder / "demo.json"
    run(
        [
            "demo",
            "--hand",
            str(hand),
            "--wrist",
            recipe.wrist,
            "--pregrasp",
            recipe.pregrasp,
            "--close",
            recipe.close,
            "--seed",
            str(seed),
            "--out",
            str(demo),
            "--cloud-out",
            str(folder / "demo.pcd"),
            "--png",
            str(folder / "demo.png"),
        ]
    )
    model = folder / "model.json"
    run(["learn", "--demo", str(demo), "--method", method, "--seed", str(seed), "--out", str(model)])
    return model


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("out_dir", type=Path, help="folder for every hand's files")
    ap.add_argument("--hands", default=",".join(HANDS), help=f"comma-separated, of {', '.join(HANDS)}")
    ap.add_argument("--method", default="gmm", choices=("gmm", "kde"))
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args(argv)
    names = [h for h in args.hands.split(",") if h]
    unknown = [h for h in names if h not in HANDS]
    if unknown:
        ap.error(f"--hands: unknown {', '.join(unknown)} (known: {', '.join(HANDS)})")
    for name in names:
        model = make(HANDS[name], args.out_dir, args.method, args.seed)
        print(f"{name}: {model}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
