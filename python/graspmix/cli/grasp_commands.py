"""demo, learn, synthesize: from a demonstration to grasps on a new cloud."""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from .. import _core
from ..io import data_path
from ..io.checks import MAX_COMPONENTS, MAX_ITERATIONS
from ..model import GraspModel, default_model_path, learn
from ..model.grasp_frames import opening_widths
from ..model.grasps import infeasible_unwarned
from ..model.settings import METHODS, LearnSettings
from ..perception import kind_name, parse_target
from .common import (
    CliError,
    float_in,
    input_path,
    int_in,
    output_file,
    parse_floats,
    parse_joints,
    picture_file,
    seed,
    urdf_path,
)
from .synthesis_flags import add_synthesis_arguments, list_settings, synthesis_options
from .views import add_view_arguments, input_keywords, known_plane


def cmd_demo(args: argparse.Namespace) -> int:
    from ..sim.demonstration import record_demonstration

    wrist = parse_floats(args.wrist, 7, "--wrist")
    demo = record_demonstration(
        args.object,
        args.hand,
        wrist,
        parse_joints(args.pregrasp, "--pregrasp"),
        parse_joints(args.close, "--close"),
        grip_force=args.force,
        max_steps=args.max_steps,
        seed=args.seed,
    )
    out = Path(args.out)
    if args.cloud_out:
        _core.save_cloud(args.cloud_out, demo.cloud)
        demo.cloud_path = Path(args.cloud_out).resolve()
    demo.save(out)
    print(f"demonstration: {len(demo.cloud)} object points; the hand closed on the object")
    for line in describe_opening(demo):
        print(f"  {line}")
    print(f"wrote {out}")
    if args.png:
        from ..viz.demonstration import plot_demonstration

        plot_demonstration(demo, args.png)
        print(f"wrote {args.png}")
    return 0


def cmd_learn(args: argparse.Namespace) -> int:
    t0 = time.perf_counter()
    demos = args.demo or [str(data_path("demos", "box_wsg50.json"))]
    model = learn(
        demos,
        args.method,
        n_components=args.components,
        kde_position_bandwidth=args.kde_position_bandwidth,
        kde_orientation_bandwidth=args.kde_orientation_bandwidth,
        kde_feature_bandwidth=args.kde_feature_bandwidth,
        gmm_reg_covar=args.gmm_reg_covar,
        seed=args.seed,
        max_distance=args.max_distance,
    )
    model.save(args.out)
    print(f"learnt a {model.method} model of {len(model.types)} grasp type(s) in {time.perf_counter() - t0:.2f} s")
    for t in model.types:
        ref = f", reference log L {t.log_reference:.2f}" if len(model.types) > 1 else ""
        print(
            f"  {t.name}: contact models for "
            + ", ".join(f"{m.link_name} ({m.n_points} points)" for m in t.synthesizer.contact_models)
            + ref
        )
    print(f"wrote {args.out}")
    return 0


def _demo_file(text: str) -> str:
    """The file of --demo PATH or NAME=PATH."""
    return text.split("=", 1)[1] if "=" in text else text


def _demo_spec(text: str) -> str:
    """--demo PATH or NAME=PATH: the file must exist."""
    input_path(_demo_file(text))
    return text


_demo_spec.file_of = _demo_file  # the file the command reads (check_distinct_files)


GAP_LABEL = "opening: finger gap (m)"  # what synthesize and demo print for a hand with two fingertip links
JOINTS_LABEL = "grasp joints (m or rad)"  # and for any other hand, or beside the gap


def joints_text(joints: dict) -> str:
    return ", ".join(f"{k}={v:.4f}" for k, v in joints.items())


def describe_opening(demo) -> list:
    """The lines demo prints of a recorded grasp, in the quantity synthesize prints: the finger gap at the grasp
    and at the pre-grasp (Grasp.opening_width's rule: grasp_frames.opening_widths), then the joints (m or rad,
    the URDF's units; a prismatic joint's value is not the gap: the WSG 50's is half of it)."""
    hand = _core.Hand.from_urdf(str(demo.hand_path))
    grasp, pre = opening_widths(hand, [demo.grasp_joints, demo.pregrasp_joints])
    lines = [] if grasp is None else [f"{GAP_LABEL}: {grasp:.4f} at the grasp, {pre:.4f} at the pre-grasp"]
    return lines + [f"{JOINTS_LABEL}: {joints_text(demo.grasp_joints)} (pre-grasp {joints_text(demo.pregrasp_joints)})"]


def print_grasps(grasps, top: int) -> None:
    """A table of the best `top` grasps: log-likelihood, every expert's term, wrist position, and the opening:
    for a two-finger hand the gap between the fingers in m (from the hand's forward kinematics at the grasp
    joints: Grasp.opening_width), else the grasp joints (m or rad, the URDF's units)."""
    rows = grasps.grasps[:top]
    if not rows:
        return
    keys = list(rows[0].experts.keys())
    short = [k.replace("contact/", "Q:") for k in keys]
    head = " ".join(f"{k:>14}" for k in short)
    gap = all(g.opening_width is not None for g in rows)
    last = GAP_LABEL if gap else JOINTS_LABEL
    typed = any(g.type for g in rows)
    kind = f" {'type':>14}" if typed else ""
    print(f"{'rank':>4} {'object':>6}{kind} {'log L':>9} {head}   wrist position (m)        {last}")
    for g in rows:
        terms = " ".join(f"{g.experts[k]:>14.3f}" for k in keys)
        pos = ", ".join(f"{x:+.3f}" for x in g.T_world_wrist[:3])
        if gap:
            opening = f"{g.opening_width:.4f}"
        else:
            opening = joints_text(g.grasp_joints)
        on = g.object
        kind = f" {g.type or '-':>14}" if typed else ""
        print(
            f"{g.rank:>4} {'-' if on is None else on['index']:>6}{kind} {g.log_likelihood:>9.3f} {terms}   "
            f"[{pos}]   {opening}"
        )


def describe_scene(scene, targets: list) -> str:
    """One line: the support plane (found, given or none) and the objects, the targets among them."""
    plane = "given" if scene.plane_given else ("found" if scene.plane_found else "none")
    objects = ", ".join(
        f"{o.index}{'*' if o.index in targets else ''} ({o.n_points} pts at "
        + ",".join(f"{v:+.3f}" for v in o.centroid)
        + (f"; {kind_name(c.kind)} +{len(c.points)} pts" if c is not None and len(c.points) else "")
        + ")"
        for o, c in zip(scene.objects, scene.completions)
    )
    return f"support plane {plane}; {len(scene.objects)} objects (* = target): {objects}"


def _model_for(args) -> tuple[GraspModel, Path]:
    """The model of --model (or the bundled one of --method), checked against --method and --hand."""
    model_path = Path(args.model) if args.model else default_model_path(args.method or "gmm")
    model = GraspModel.load(model_path)
    if args.method and args.model and model.method != args.method:
        raise CliError(f"--method {args.method} but the model {model_path} is a {model.method} model")
    if args.hand and Path(args.hand).resolve() != model.hand_path.resolve():
        other = _core.Hand.from_urdf(args.hand)
        if other.name != model.hand.name or other.link_names != model.hand.link_names:
            raise CliError(
                f"the model {model_path.name} was learnt for hand '{model.hand.name}', not '{other.name}' ({args.hand})"
            )
    return model, model_path


def cmd_synthesize(args: argparse.Namespace) -> int:
    if args.list_settings:
        print(list_settings())
        return 0
    given = input_keywords(args, "the scene or object cloud to grasp")
    model, model_path = _model_for(args)
    axis = parse_floats(args.approach_axis, 3, "--approach-axis") if args.approach_axis else None
    opts, plane = synthesis_options(args), known_plane(args)
    with infeasible_unwarned():  # said below in the command's own words, after the grasps are written
        grasps = model.synthesize(
            options=opts, plane=plane, target=args.target, approach_axis=axis, types=args.types, **given
        )
    t = grasps.timing
    source = args.cloud or args.depth
    print(f"{model.method} model '{model_path.name}' on {source}: {len(grasps.surface.points)} surface points")
    print(describe_scene(grasps.scene, grasps.targets))
    for note in grasps.scene.notes:
        print(f"graspmix_cli synthesize: note: {note}", file=sys.stderr)
    print(
        f"time: features {t['features'] * 1e3:.0f} ms (segmentation {t['segmentation'] * 1e3:.0f} ms), "
        f"query densities {t['query'] * 1e3:.0f} ms, "
        f"sampling+ranking {t['sampling'] * 1e3:.0f} ms, optimisation {t['optimisation'] * 1e3:.0f} ms, "
        f"total {t['total'] * 1e3:.0f} ms ({grasps.evaluations} grasp evaluations, {grasps.rejected} samples rejected "
        f"by hard constraints)"
    )
    print_grasps(grasps, args.top)
    grasps.save(args.out)
    print(f"wrote {args.out} ({len(grasps)} grasps, best first)")
    if len(grasps) and grasps.n_feasible == 0:
        print(f"graspmix_cli synthesize: warning: {grasps.no_feasible_message(NO_GRASP_ADVICE)}", file=sys.stderr)
    if args.png:
        grasps.plot(args.png, top=max(min(args.top, 3), 1))
        print(f"wrote {args.png}")
    return 0


# What may help when no grasp passed, in the command's flags (GraspSet.no_feasible_message).
NO_GRASP_ADVICE = (
    "the grasps written are the least bad. More --samples or another --seed may find one; with --collision occupancy "
    "the cloud must hold the table around the objects (a whole depth image), or the space beside them is unseen and "
    "counts as solid"
)


COMMANDS = ("demo", "learn", "synthesize")


def add_parsers(sub) -> None:
    _add_demo(sub)
    _add_learn(sub)
    _add_synthesize(sub)


def _add_demo(sub) -> None:
    from ..model.demonstration import DEMO_GRIP_FORCE, DEMO_MAX_STEPS

    s = sub.add_parser("demo", help="record a demonstrated grasp in simulation (pybullet) as a demonstration file")
    s.add_argument(
        "--object",
        type=input_path,
        default=str(data_path("objects", "box.urdf")),
        help="object URDF (a path, or relative to pybullet_data); default: the bundled box",
    )
    s.add_argument(
        "--hand", type=urdf_path, default=str(data_path("hands", "wsg50.urdf")), help="hand URDF (default: WSG 50)"
    )
    s.add_argument("--wrist", required=True, help="wrist pose x,y,z,qx,qy,qz,qw in the world (m)")
    s.add_argument("--pregrasp", required=True, help="pre-grasp joints name=value,...")
    s.add_argument(
        "--close", required=True, help="joints to close towards, name=value,... (the fingers stop on contact)"
    )
    s.add_argument("--force", type=float_in(gt=0.0), default=DEMO_GRIP_FORCE, help="motor force limit (N or N m)")
    s.add_argument(
        "--max-steps",
        type=int_in(1, MAX_ITERATIONS),
        default=DEMO_MAX_STEPS,
        help="simulation steps (240 Hz) the closing fingers get to come to rest",
    )
    s.add_argument("--seed", type=seed, default=0)
    s.add_argument("--out", type=output_file, required=True, help="demonstration file (.json)")
    s.add_argument("--png", type=picture_file, help="draw the object cloud and the hand at pre-grasp and grasp")
    s.add_argument(
        "--cloud-out", type=output_file, help="write the object cloud to this PCD and refer to it (default: inline)"
    )
    s.set_defaults(func=cmd_demo)


def _add_learn(sub) -> None:
    s = sub.add_parser("learn", help="learn contact and configuration models from demonstrations (one grasp type each)")
    s.add_argument(
        "--demo",
        type=_demo_spec,
        action="append",
        help="demonstration file, or NAME=FILE to name its grasp type (default name: the file's stem); repeat for "
        "several grasp types of one hand (default: the bundled box demonstration)",
    )
    s.add_argument("--method", default="gmm", choices=list(METHODS))
    s.add_argument(
        "--components",
        type=int_in(1, MAX_COMPONENTS),
        default=LearnSettings.n_components,
        help="K of the contact mixtures (GMM)",
    )
    s.add_argument(
        "--kde-position-bandwidth",
        type=float_in(gt=0.0),
        default=LearnSettings.kde_position_bandwidth,
        help=f"m: std of KDE's position kernels ({LearnSettings.kde_position_bandwidth})",
    )
    s.add_argument(
        "--kde-orientation-bandwidth",
        type=float_in(gt=0.0),
        default=LearnSettings.kde_orientation_bandwidth,
        help=f"rad: std of KDE's rotation kernels ({LearnSettings.kde_orientation_bandwidth})",
    )
    s.add_argument(
        "--kde-feature-bandwidth",
        type=float_in(gt=0.0),
        default=LearnSettings.kde_feature_bandwidth,
        help=f"std of KDE's curvature kernels ({LearnSettings.kde_feature_bandwidth})",
    )
    s.add_argument(
        "--gmm-reg-covar",
        type=float_in(gt=0.0),
        default=LearnSettings.gmm_reg_covar,
        help=f"added to every covariance diagonal of GMM's contact mixtures ({LearnSettings.gmm_reg_covar:g})",
    )
    s.add_argument(
        "--max-distance",
        type=float_in(gt=0.0),
        default=LearnSettings.max_distance,
        help="m: object points this close to a link are its contacts",
    )
    s.add_argument("--seed", type=seed, default=LearnSettings.seed)
    s.add_argument("--out", type=output_file, required=True, help="model file (.json)")
    s.set_defaults(func=cmd_learn)


def _target(text: str) -> str:
    try:
        parse_target(text)
    except ValueError as e:
        raise argparse.ArgumentTypeError(str(e)) from None
    return text


def _add_synthesize(sub) -> None:
    s = sub.add_parser("synthesize", help="synthesise, rank and optimise grasps on a cloud")
    s.add_argument(
        "--cloud", type=input_path, help="the scene or object cloud (.pcd, .ply, .npy); required unless --depth"
    )
    s.add_argument(
        "--model",
        type=input_path,
        help="learnt model (.json); default: the bundled box demonstration model of --method",
    )
    s.add_argument("--method", choices=list(METHODS), default=None, help="with no --model: which bundled model (gmm)")
    s.add_argument("--hand", type=urdf_path, help="hand URDF; must be the model's hand")
    s.add_argument("--types", help="comma-separated grasp types of the model to sample (default: all)")
    s.add_argument(
        "--approach-axis", help="prefer wrists approaching along this world axis, e.g. 0,0,-1 for top grasps"
    )
    s.add_argument(
        "--target",
        type=_target,
        default="all",
        help="which object to grasp: all (default: any, best first), an object index (graspmix_cli segment), "
        "point:x,y,z (the object nearest the point), largest, nearest (to the camera)",
    )
    add_view_arguments(s)
    add_synthesis_arguments(s)
    s.add_argument("--list-settings", action="store_true", help="print every synthesis setting (--set) and exit")
    s.add_argument("--top", type=int_in(0), default=5, help="grasps to print")
    s.add_argument("--out", type=output_file, default="grasps.json", help="grasps file (default grasps.json)")
    s.add_argument("--png", type=picture_file, help="draw the cloud and the best grasps' hands")
    s.set_defaults(func=cmd_synthesize)
