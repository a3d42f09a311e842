"""Issue 27's trial of any hand, repeated as a user would: held-out objects, four noisy cameras, each hand's model.

    python scripts/hands_trial.py OUT [--hands wsg50,panda,xarm,pr2] [--models DIR] [--objects FILE] [--count 12]
                                      [--seed 0] [--views 4]

For each of the first --count objects of --objects (default data/objects/clutter_test.txt, held out: nothing may
be tuned on them), alone on the table at its rest pose, with the project's command line (a subprocess per step,
each command written to OUT/commands.sh so it can be typed again):
  graspmix_cli acquire --object OBJ --views 4 --noise --seed S --out OUT/clouds/NN_NAME.pcd    (S = --seed + NN)
  graspmix_cli synthesize --model M --cloud OUT/clouds/NN_NAME.pcd --out OUT/HAND/NN_NAME.json   (the defaults)
then the best grasp is executed by the independent pybullet harness (graspmix.sim.pybullet_reference.
execute_pybullet, the same protocol as `graspmix_cli execute`: the fingers close until they stop, then a 20 cm
lift) with the model's hand URDF and the object at the pose acquire placed it at (graspmix.sim.rest_pose).
The WSG 50's model is the bundled data/models/box_wsg50_gmm.json; the others are DIR/NAME/model.json, made by
scripts/hand_models.py DIR (run here for those missing).

Prints per hand the objects lifted (and the failed ones with their outcome), the median wall time of one
`synthesize` command (and of its own total, timing_s.total of the grasps file) and its ratio to the WSG 50's;
writes OUT/results.json (every attempt) and OUT/results.md (the table). Bad arguments: one line on stderr,
exit status 2.
"""

from __future__ import annotations

import json
import os
import shlex
import statistics
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(Path(__file__).resolve().parent))

from graspmix.cli.common import OneLineParser, int_in, seed  # noqa: E402
from graspmix.io import read_objects_file, resolve_path  # noqa: E402
from graspmix.io.checks import check_output_folder  # noqa: E402
from hand_models import HANDS  # noqa: E402  (the recipes of the pybullet_data hands)

WSG50 = "wsg50"
NAMES = (WSG50, *HANDS)
DEFAULT_OBJECTS = REPO / "data" / "objects" / "clutter_test.txt"
RESULTS_FORMAT = "graspmix.hands_trial/1"


class StepFailed(Exception):
    """A command of the trial failed: its command line and the last line it printed on stderr."""


class Runner:
    """Runs graspmix_cli commands as subprocesses (this Python, so the same graspmix) and logs them."""

    def __init__(self, log: Path):
        self.log = log
        log.write_text("#!/bin/sh\n# the commands of scripts/hands_trial.py, in the order they ran\n")

    def __call__(self, args: list[str]) -> tuple[str, float]:
        """(stdout, wall time in s); StepFailed when the command exits non-zero."""
        with self.log.open("a") as f:
            f.write("graspmix_cli " + shlex.join(args) + "\n")
        t0 = time.perf_counter()
        done = subprocess.run([sys.executable, "-m", "graspmix.cli", *args], capture_output=True, text=True)
        wall = time.perf_counter() - t0
        if done.returncode != 0:
            lines = done.stderr.strip().splitlines() or [f"exit status {done.returncode}"]
            raise StepFailed(f"graspmix_cli {args[0]} ({done.returncode}): {lines[-1]}")
        return done.stdout, wall


def model_paths(names: list[str], models_dir: Path) -> dict[str, Path]:
    """Each hand's model; the missing pybullet_data hands' are made by scripts/hand_models.py."""
    from graspmix import default_model_path

    paths = {n: default_model_path("gmm") if n == WSG50 else models_dir / n / "model.json" for n in names}
    missing = [n for n in names if not paths[n].is_file()]
    if missing:
        print(f"making the models of {', '.join(missing)}: scripts/hand_models.py {models_dir}", flush=True)
        cmd = [sys.executable, str(REPO / "scripts" / "hand_models.py"), str(models_dir), "--hands", ",".join(missing)]
        done = subprocess.run(cmd, capture_output=True, text=True)
        if done.returncode != 0:
            raise StepFailed(f"scripts/hand_models.py: {(done.stderr.strip().splitlines() or ['failed'])[-1]}")
    return paths


def model_hand(model: Path) -> Path:
    """The model's hand URDF, as the model file names it (relative to the file, package:// or pybullet_data://)."""
    doc = json.loads(model.read_text())
    return resolve_path(doc["hand"], model.resolve().parent)


def attempt(run: Runner, obj: str, cloud: Path, model: Path, hand: Path, pose, grasps: Path) -> dict:
    """synthesize on the cloud, execute the best grasp in pybullet: one row."""
    from graspmix import GraspSet
    from graspmix.sim.execution import CLOSING
    from graspmix.sim.pybullet_reference import execute_pybullet

    row = {"object": obj, "cloud": cloud.name, "grasps": str(grasps.relative_to(grasps.parents[1]))}
    try:
        _, wall = run(["synthesize", "--model", str(model), "--cloud", str(cloud), "--out", str(grasps)])
    except StepFailed as e:
        return dict(row, lifted=False, outcome="synthesis failed", error=str(e), synthesize_s=None, total_s=None)
    gs = GraspSet.load(grasps)
    row.update(synthesize_s=wall, total_s=float(gs.timing["total"]), load=os.getloadavg()[0])
    if len(gs) == 0:
        return dict(row, lifted=False, outcome="no grasps")
    best = gs.best()
    r = execute_pybullet(obj, best, hand=hand, object_pose=pose, **CLOSING["full"])
    return dict(
        row,
        lifted=bool(r["success"]),
        outcome=r["reason"],
        lift_height=float(r["lift_height"]),
        contact_count=int(r["contact_count"]),
        log_likelihood=float(best.log_likelihood),
        T_world_wrist=[float(v) for v in best.T_world_wrist],
    )


def _median(values) -> float | None:
    values = [v for v in values if v is not None]
    return statistics.median(values) if values else None


def summarise(rows: dict[str, list[dict]]) -> dict[str, dict]:
    """Per hand: lifted of n, the failures, the median times and their ratio to the WSG 50's."""
    out = {}
    for name, rs in rows.items():
        out[name] = {
            "lifted": sum(r["lifted"] for r in rs),
            "n": len(rs),
            "failed": [{"object": r["object"], "outcome": r["outcome"]} for r in rs if not r["lifted"]],
            "median_synthesize_s": _median(r["synthesize_s"] for r in rs),
            "median_total_s": _median(r["total_s"] for r in rs),
        }
    ref = out.get(WSG50, {}).get("median_synthesize_s")
    for s in out.values():
        s["ratio_to_wsg50"] = s["median_synthesize_s"] / ref if ref and s["median_synthesize_s"] else None
    return out


def _fmt(v, spec: str) -> str:
    return "-" if v is None else format(v, spec)


def table(summary: dict[str, dict]) -> str:
    lines = [
        "| hand | lifted | synthesize, median (s) | its total (s) | ratio to WSG 50 | failed (outcome) |",
        "| --- | --- | --- | --- | --- | --- |",
    ]
    for name, s in summary.items():
        failed = ", ".join(f"{Path(f['object']).stem} ({f['outcome']})" for f in s["failed"]) or "none"
        lines.append(
            f"| {name} | {s['lifted']} of {s['n']} | {_fmt(s['median_synthesize_s'], '.2f')} | "
            f"{_fmt(s['median_total_s'], '.2f')} | {_fmt(s['ratio_to_wsg50'], '.2f')} | {failed} |"
        )
    return "\n".join(lines) + "\n"


def parse_args(argv):
    ap = OneLineParser(prog="hands_trial.py", description=__doc__.split("\n\n")[0])
    ap.add_argument("out", type=Path, help="folder for the clouds, grasps files, commands.sh and results")
    ap.add_argument("--hands", default=",".join(NAMES), help=f"comma-separated, of {', '.join(NAMES)} (default all)")
    ap.add_argument(
        "--models", type=Path, help="folder of NAME/model.json (scripts/hand_models.py DIR); default OUT/models"
    )
    ap.add_argument("--objects", type=Path, default=DEFAULT_OBJECTS, help="objects file (default clutter_test.txt)")
    ap.add_argument("--count", type=int_in(1), default=12, help="the first COUNT objects of the list (default 12)")
    ap.add_argument("--seed", type=seed, default=0, help="object NN's acquisition seed is SEED + NN (default 0)")
    ap.add_argument("--views", type=int_in(2, 64), default=4, help="cameras of the ring (default 4)")
    args = ap.parse_args(argv)
    names = [h for h in args.hands.split(",") if h]
    unknown = [h for h in names if h not in NAMES]
    if unknown or not names:
        ap.error(f"--hands: unknown {', '.join(unknown) or 'none given'} (known: {', '.join(NAMES)})")
    if len(set(names)) != len(names):
        ap.error(f"--hands: a hand is listed twice: {args.hands}")
    args.hands = names
    try:
        check_output_folder(args.out, "OUT")
        args.object_list = read_objects_file(args.objects)
    except ValueError as e:
        ap.error(str(e))
    if len(args.object_list) < args.count:
        ap.error(f"--count {args.count}: {args.objects} lists {len(args.object_list)} objects")
    return args


def main(argv: list[str] | None = None) -> int:
    args = parse_args(argv)
    from graspmix.sim import rest_pose

    out = args.out
    (out / "clouds").mkdir(parents=True, exist_ok=True)
    for name in args.hands:
        (out / name).mkdir(exist_ok=True)
    objects = args.object_list[: args.count]
    run = Runner(out / "commands.sh")
    try:
        models = model_paths(args.hands, args.models or out / "models")
        hands = {n: model_hand(m) for n, m in models.items()}
    except (StepFailed, ValueError, OSError, KeyError) as e:
        print(f"hands_trial.py: error: {e}", file=sys.stderr)
        return 2
    load0 = os.getloadavg()
    t0 = time.perf_counter()
    rows: dict[str, list[dict]] = {n: [] for n in args.hands}
    placed = []
    # Object by object, every hand on the same cloud in turn, so a change of the machine's load falls on all.
    for i, obj in enumerate(objects):
        stem = f"{i:02d}_{Path(obj).stem}"
        cloud = out / "clouds" / f"{stem}.pcd"
        acq = ["acquire", "--object", obj, "--views", str(args.views), "--noise", "--seed", str(args.seed + i)]
        try:
            run([*acq, "--out", str(cloud)])
        except StepFailed as e:
            print(f"hands_trial.py: error: {e}", file=sys.stderr)
            return 1
        pose = rest_pose(obj)  # where acquire put it (`execute --object`'s default too)
        placed.append({"object": obj, "seed": args.seed + i, "pose": [float(v) for v in pose], "cloud": cloud.name})
        said = []
        for name in args.hands:
            r = attempt(run, obj, cloud, models[name], hands[name], pose, out / name / f"{stem}.json")
            rows[name].append(r)
            t = "" if r["synthesize_s"] is None else f" {r['synthesize_s']:.1f} s"
            said.append(f"{name} {'lifted' if r['lifted'] else r['outcome']}{t}")
        print(f"[{i + 1}/{len(objects)}] {obj}: " + "; ".join(said), flush=True)
    summary = summarise(rows)
    doc = {
        "format": RESULTS_FORMAT,
        "objects_file": str(args.objects),
        "views": args.views,
        "noise": True,
        "seed": args.seed,
        "closing": "full",
        "executor": "graspmix.sim.pybullet_reference.execute_pybullet",
        "models": {n: str(m) for n, m in models.items()},
        "hands": {n: str(h) for n, h in hands.items()},
        "objects": placed,
        "load_average": {"start": list(load0), "end": list(os.getloadavg()), "cpus": os.cpu_count()},
        "wall_s": time.perf_counter() - t0,
        "summary": summary,
        "attempts": rows,
    }
    (out / "results.json").write_text(json.dumps(doc, indent=1) + "\n")
    text = table(summary)
    load = f"load average {load0[0]:.1f} at the start, {os.getloadavg()[0]:.1f} at the end, {os.cpu_count()} CPUs"
    (out / "results.md").write_text(
        f"{len(objects)} objects of {args.objects.name}, {args.views} noisy views, seeds {args.seed}-"
        f"{args.seed + len(objects) - 1}; {load}\n\n{text}"
    )
    print(text + load + f"; wrote {out / 'results.json'}, {out / 'results.md'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
