"""graspmix_cli hand: what a hand URDF holds as graspmix reads it (links, joints, limits, mimic
relations, the independent joints a demonstration sets, the wrist frame, the approach axis, closing
directions, the opening width of a two-finger gripper or the diameter three or more fingers around the
approach axis leave free), and a picture of it at its limits."""

from __future__ import annotations

import json

from .common import CliError, output_file, parse_floats, picture_file, urdf_path

COMMANDS = ("hand",)


def add_parsers(sub) -> None:
    s = sub.add_parser("hand", help="links, joints, frames and opening of a hand URDF; --png draws it at its limits")
    s.add_argument("--urdf", type=urdf_path, required=True, help="the hand's URDF (its root link is the wrist)")
    s.add_argument("--png", type=picture_file, help="draw the hand at its lower and upper joint limits")
    s.add_argument("--json", action="store_true", help="print the description as JSON instead")
    s.add_argument("--wrist-link", help="--urdf is a robot's: cut the hand below this link (the new wrist) ...")
    s.add_argument("--out", type=output_file, help="... into this hand-only URDF, then describe it")
    s.add_argument(
        "--approach-axis",
        help="X,Y,Z: the approach axis in the wrist frame, written with --out into the hand's <graspmix> element "
        "(default: inferred, the direction from the wrist to the fingertips)",
    )
    s.add_argument(
        "--fingertips",
        help="A,B,...: the fingertip links, written with --out into the hand's <graspmix> element (default: "
        "inferred, the distal link of each finger chain)",
    )
    s.set_defaults(func=cmd_hand)


def cmd_hand(args) -> int:
    from ..model.hands import describe_hand, hand_urdf_from_robot, write_hand_axes

    axes = args.approach_axis is not None or args.fingertips is not None
    if args.out is None and (args.wrist_link is not None or axes):
        raise CliError("--wrist-link, --approach-axis and --fingertips write a hand: give --out")
    if args.out is not None and args.wrist_link is None and not axes:
        raise CliError("--out writes a hand cut with --wrist-link or given --approach-axis/--fingertips")
    if args.wrist_link is not None:
        args.urdf = str(hand_urdf_from_robot(args.urdf, args.wrist_link, args.out))
    if axes:
        approach = None if args.approach_axis is None else parse_floats(args.approach_axis, 3, "--approach-axis")
        tips = None if args.fingertips is None else [n for n in args.fingertips.split(",") if n]
        args.urdf = str(write_hand_axes(args.urdf, args.out, approach, tips))
    if args.out is not None:
        print(f"wrote {args.out}")
    if args.png:
        from ..viz.hand import plot_hand

        info = plot_hand(args.urdf, args.png)
    else:
        info = describe_hand(args.urdf)
    if args.json:
        print(json.dumps(info, indent=1, allow_nan=False))
    else:
        print("\n".join(format_hand(info)))
    if args.png:
        print(f"wrote {args.png}")
    return 0


def _limits(j: dict) -> str:
    if j["type"] == "fixed":
        return ""
    unit = "m" if j["type"] == "prismatic" else "rad"
    lo, hi = ("-inf" if j["lower"] is None else f"{j['lower']:g}"), ("inf" if j["upper"] is None else f"{j['upper']:g}")
    return f"[{lo}, {hi}] {unit}"


def _closing(sign) -> str:
    return {1: "closes as it increases", -1: "closes as it decreases", 0: "neither opens nor closes the fingers"}.get(
        sign, ""
    )


def format_hand(info: dict) -> list[str]:
    """The description as lines of text."""
    a = info["approach_axis"]
    lines = [f"hand {info['name']} ({info['urdf']})", f"wrist frame: link '{info['wrist']}' (the URDF's root link)"]
    lines.append(f"links ({len(info['links'])}):")
    for link in info["links"]:
        moved = f"moved by {', '.join(link['moved_by'])}" if link["moved_by"] else "rigid with the wrist"
        tip = ", fingertip" if link["fingertip"] else ""
        lines.append(f"  {link['name']}: collision {', '.join(link['shapes']) or 'none'}; {moved}{tip}")
    lines.append(f"joints ({len(info['joints'])}):")
    for j in info["joints"]:
        kind = ", independent" if j["independent"] else (f", mimics {j['mimic']}" if j["mimic"] else "")
        axis = "" if j["type"] == "fixed" else f" axis {_vec(j['axis'])} {_limits(j)}"
        closing = f", {_closing(j['closing'])}" if j["closing"] is not None else ""
        lines.append(f"  {j['name']} ({j['type']}{kind}): {j['parent']} -> {j['child']}{axis}{closing}")
    for name, m in info["mimic"].items():
        lines.append(f"  mimic: {name} = {m['multiplier']:g} * {m['joint']} + {m['offset']:g}")
    lines.append(f"independent joints (what a demonstration sets): {', '.join(info['independent_joints']) or 'none'}")
    source = {"urdf": "given by the URDF's <graspmix> element", "set": "set"}.get(
        a["source"],
        f"inferred: the wrist-to-fingertips direction, snapped to a wrist axis within {a['snap_deg']:g} deg",
    )
    lines.append(f"approach axis: {_vec(a['axis'])} of the wrist frame ({source})")
    lines.append(f"fingertips: {', '.join(info['fingertips']) or 'none'} (contact quality's fingers; the opening)")
    if a["angle_deg"] is not None:
        verdict = "agrees" if a["agrees"] else "does NOT agree: give the axis with --approach-axis X,Y,Z --out"
        lines.append(
            f"  the fingertips' mean lies along {_vec(a['fingers_direction'])} from the wrist, "
            f"{a['angle_deg']:.0f} deg from it ({verdict})"
        )
    w = info["opening_width"]
    if w:
        sides = " | ".join(", ".join(side) for side in info["fingers"])
        lines.append(
            f"two-finger gripper ({sides}): opening {1000 * w['lower'] + 0.0:.1f} mm at the lower limits, "
            f"{1000 * w['upper'] + 0.0:.1f} mm at the upper limits"
        )
    d = info.get("opening_diameter")
    if d:
        lines.append(
            f"{len(info['fingertips'])} fingertips around the approach axis: opening (the circle about the axis "
            f"they leave free) {1000 * d['lower'] + 0.0:.1f} mm across at the lower limits, "
            f"{1000 * d['upper'] + 0.0:.1f} mm at the upper limits"
        )
    return lines


def _vec(v) -> str:
    return "[" + ", ".join(f"{x + 0.0:.3g}" for x in v) + "]"
