"""The segment a named point selected, seen from the side, for every attempt of a named run that lifted a neighbour.

    python scripts/named_segments_figure.py RUN OUT.png

RUN: a `graspmix_cli clutter --task named` run (its clutter.json and named_attempts.csv[.gz]). Each attempt that
lifted a neighbour ("wrong object", "two objects lifted") is rebuilt: its scene placed and observed again (the
protocol's seeds), the scene segmented as the attempt's synthesis segmented it (the run's settings, the attempt's
seed and target; few samples, since only the segmentation is drawn; checked against the segment the attempt
recorded), and the segment the named point selects drawn from the camera's side (across the view against height),
each point coloured by whether the simulator puts it on the named object.
"""

from __future__ import annotations

import argparse
import json
import warnings
from pathlib import Path

import numpy as np


def side_view(ax, points, on_target, point, camera, title: str) -> None:
    """Points (n, 3) across the camera's horizontal view direction (cm) against height (cm)."""
    forward = points.mean(0) - camera
    forward[2] = 0.0
    forward /= np.linalg.norm(forward)
    across = np.array([-forward[1], forward[0], 0.0])
    for mask, colour, name in [
        (on_target, "tab:blue", "named object"),
        (~on_target, "tab:orange", "not the named object"),
    ]:
        ax.scatter(points[mask] @ across * 100, points[mask, 2] * 100, s=2, c=colour, label=f"{name} ({mask.sum()})")
    ax.scatter([point @ across * 100], [point[2] * 100], c="k", marker="x", s=60, label="named point")
    ax.set_title(title, fontsize=9)
    ax.set_aspect("equal")
    ax.legend(fontsize=6, loc="upper left")
    ax.set_xlabel("across the view (cm)", fontsize=7)
    ax.set_ylabel("height (cm)", fontsize=7)
    ax.tick_params(labelsize=6)


def load_named_run(run: Path):
    """A named run's protocol, its GMM model (the segmentation is the same for every method) and its attempts;
    exits with one line naming the run when it is not a named run of `graspmix_cli clutter`."""
    from graspmix.clutter.named import named_rows
    from graspmix.clutter.protocol import clutter_protocol_from_json
    from graspmix.experiment.attempt import cached_model

    try:
        p = clutter_protocol_from_json(json.loads((run / "clutter.json").read_text())["protocol"])
        rows = named_rows(run)
    except (OSError, ValueError, KeyError) as e:
        raise SystemExit(f"{run}: not a named run of graspmix_cli clutter ({e})") from None
    return p, cached_model(str(p.model_path("gmm").resolve())), rows


def rebuilt_segment(p, model, r: dict):
    """A named attempt's scene rebuilt (placed and observed again from the protocol's seeds) and segmented as its
    synthesis segmented it (the run's settings, the attempt's seed and target; few samples, only the segmentation is
    used): (named scene, named point, the segment the point selects, the simulator's label of each of its points).
    Exits when the rebuilt segment is not the one the attempt recorded."""
    from graspmix.clutter.named import named_scene, point_target
    from graspmix.model.grasps import NoFeasibleGraspWarning

    ns = named_scene(p, r["mode"], int(r["scene"]))
    point = ns.point(ns.picks[int(r["pick"])])
    # the attempt's seed (it seeds the segmentation's RANSAC too); few samples: the grasps are not used
    options = p.synthesis.updated(
        {"seed": int(r["synthesis_seed"]), "sampling.n_samples": 10, "sampling.n_optimise": 1}
    )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", NoFeasibleGraspWarning)
        scene = p.synthesize(model, ns.obs, options, target=point_target(point)).scene
    selected = scene.select(point_target(point))
    index = selected[0] if selected else None
    if index != int(r["named"]) or point_target(point) != "point:" + r["point"]:
        raise SystemExit(f"scene {r['scene']} pick {r['pick']}: the rebuilt scene is not the attempt's")
    obj = next(o for o in scene.objects if o.index == index)
    labels = np.asarray(p.object_labels(ns.obs))[scene.sources[obj.rows]]
    return ns, point, obj, labels


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("run", type=Path)
    ap.add_argument("out", type=Path)
    args = ap.parse_args()

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    p, model, rows = load_named_run(args.run)
    rows = [r for r in rows if r["outcome"] in ("wrong object", "two objects lifted")]
    if not rows:
        raise SystemExit(f"{args.run}: no attempt lifted a neighbour")
    cols = (len(rows) + 1) // 2
    fig, axes = plt.subplots(2, cols, figsize=(3.6 * cols, 6.4), squeeze=False)
    for ax, r in zip(axes.ravel(), rows):
        ns, point, obj, labels = rebuilt_segment(p, model, r)
        target = ns.picks[int(r["pick"])]
        camera = np.asarray(ns.obs.viewpoints)[0]
        side_view(ax, obj.points, labels == target, point, camera, f"scene {r['scene']}, pick {r['pick']}")
        print(
            f"scene {r['scene']} pick {r['pick']}: {obj.points.shape[0]} points, {np.mean(labels == target):.0%} the named object's"
        )
    for ax in axes.ravel()[len(rows) :]:
        ax.axis("off")
    fig.suptitle(
        f"The segment the named point selects, attempts that lifted a neighbour ({args.run.name})", fontsize=10
    )
    fig.tight_layout()
    fig.savefig(args.out, dpi=80)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
