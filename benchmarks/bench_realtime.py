"""The whole path from a scene cloud (table included) to ranked grasps, GMM vs KDE, models loaded once (issue 15).

    python benchmarks/bench_realtime.py [--repeats 5] [--quick] [--seed 0] [--cache DIR] [--no-noise]

Scene clouds are made by the project's own simulated cameras (graspmix.sim.scenes.make_scene, "packed",
and graspmix.sim.scene_camera.acquire_scene, as `graspmix_cli scene` + `graspmix_cli acquire --scene` do;
seeded, the depth noise model on unless --no-noise): single-object scenes (objects of
data/objects/clutter_dev.txt) seen by the ring of four cameras and by the one scene camera, several-object
scenes (5 objects, one view), and the bundled data/mug.pcd; each one-view scene also as the camera's depth image
with its intrinsics and pose (synthesize(depth=..., intrinsics=..., camera_pose=...): the image path, issue 26).
In one process, for each method, GraspModel.synthesize(..., target="largest") is called once to warm up and then --repeats
times; printed per scene kind: the median and 90th percentile of every stage of GraspSet.timing (the
segmentation's own steps under it: seg:voxel, seg:visibility, seg:outliers, seg:clusters, seg:rules for the other
rules, seg:completion for the completion and the choice of targets) and of the whole call (time.perf_counter around
it), and the KDE/GMM ratio of the medians.

Then: the CLI's wall time (`graspmix_cli synthesize --cloud data/mug.pcd`, a subprocess, median), the
wall time of `python -c "import graspmix"` (median) and the load time of graspmix._core (`python -X importtime`, its
own line, median); load_cloud on one 640x480 organised view (a binary PCD written here by numpy, NaN holes; and
the same as binary_compressed), median of 20; and the scaling of the GMM path with the raw cloud size
(5k points of a single-object scene cloud around the object, and 20k, 80k and 300k by jittered copies of them) and with n_samples
(200, 1000, 5000), flagging a stage whose time grows by more than 1.5 times the size ratio (against the
first size and the previous one). Figures only:
nothing here asserts a time. Issue 15's targets: GMM < 20 ms (single object), < 40 ms (5 objects);
KDE/GMM >= 5; CLI < 250 ms.
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import graspmix
import numpy as np
from bench_common import median_seconds
from graspmix.io import data_path, load_points

# GraspSet.timing's "features" is the total less the segmentation and the synthesiser's own stages (query,
# sampling, optimisation): the features and whatever is timed by no stage (e.g. the conversion of every sample to
# a Python grasp). "outside" (derived here) is the whole call's time less the total (what synthesize does after
# its timer stops: building the GraspSet).
STAGES = ["segmentation", "features", "query", "sampling", "optimisation", "total", "outside"]
SIZES = (5_000, 20_000, 80_000, 300_000)
SAMPLES = (200, 1000, 5000)
JITTER = 0.0005  # m: the standard deviation of the jitter of an upsampled copy
GROWTH_FLAG = 1.5  # a stage is flagged when its time ratio exceeds this times the size ratio
METHODS = ("gmm", "kde")


# -- the clouds


def _acquire(spec, views: int, noise: bool, seed: int, cameras=None) -> dict:
    """{points, viewpoints} of the scene's views, and of one view also its depth image, K and camera pose."""
    from graspmix.sim import scene_camera

    acq = scene_camera.acquire_scene(spec, views=views, noise=noise, seed=seed, keep="scene", cameras=cameras)
    out = {"points": np.ascontiguousarray(acq.points), "viewpoints": np.ascontiguousarray(acq.viewpoints)}
    if views == 1:
        cam = acq.cameras[0]
        out.update(depth=acq.depth_images[0], K=cam.pinhole().K, pose=np.asarray(cam.pose()))
    return out


def _cached(cache: Path | None, key: str, make) -> dict:
    """_acquire's arrays from cache/key.npz when there, else made (and stored when a cache is given)."""
    path = cache / f"{key}.npz" if cache is not None else None
    if path is not None and path.exists():
        with np.load(path) as f:
            if "depth" in f or "-v1-" not in key:  # a one-view cache written before the depth images were kept: remake
                return dict(f)
    arrays = make()
    if path is not None:
        path.parent.mkdir(parents=True, exist_ok=True)
        np.savez_compressed(path, **arrays)
    return arrays


def _inputs(arrays: dict, image: bool) -> dict:
    """GraspModel.synthesize's input keywords: the depth image with its intrinsics and pose, or the points."""
    if image:
        return {"depth": arrays["depth"], "intrinsics": arrays["K"], "camera_pose": arrays["pose"]}
    return {"cloud": arrays["points"], "viewpoints": arrays["viewpoints"]}


def make_clouds(args) -> dict[str, list[tuple[str, int, dict]]]:
    """{scene kind: [(name, raw points, synthesize's input keywords)]}: single-object scenes by 4 views and by 1 view
    (as points, and as the depth image with its intrinsics and pose: the image path), 5-object scenes by 1 view
    (both ways), the bundled mug."""
    from graspmix.sim import scenes

    n_single, n_multi = (1, 1) if args.quick else (3, 2)
    dev = data_path("objects", "clutter_dev.txt")
    tag = "noise" if args.noise else "clean"
    kinds: dict[str, list] = {
        k: []
        for k in (
            "single object, 4 views",
            "single object, 1 view",
            "single object, 1 depth image",
            "5 objects, 1 view",
            "5 objects, 1 depth image",
        )
    }
    for i, obj in enumerate(scenes.choose_objects(dev, n_single, args.seed)):
        seed = args.seed + i
        spec = None

        def spec_of(obj=obj, seed=seed):
            nonlocal spec
            spec = spec or scenes.make_scene([obj], "packed", seed)
            return spec

        name = f"{Path(obj).parent.name or Path(obj).stem} (seed {seed})"
        for views in (4, 1):
            key = f"single-{Path(obj).stem}-s{seed}-v{views}-{tag}"
            arrays = _cached(args.cache, key, lambda v=views, s=seed: _acquire(spec_of(), v, args.noise, s))
            n = len(arrays["points"])
            kinds[f"single object, {views} view{'s' if views > 1 else ''}"].append((name, n, _inputs(arrays, False)))
            if views == 1:
                kinds["single object, 1 depth image"].append((name, arrays["depth"].size, _inputs(arrays, True)))
    for i in range(n_multi):
        seed = args.seed + 100 + i
        objs = scenes.choose_objects(dev, 5, seed)
        key = f"multi5-s{seed}-v1-{tag}"
        arrays = _cached(
            args.cache, key, lambda o=objs, s=seed: _acquire(scenes.make_scene(o, "packed", s), 1, args.noise, s)
        )
        kinds["5 objects, 1 view"].append((f"5 objects (seed {seed})", len(arrays["points"]), _inputs(arrays, False)))
        kinds["5 objects, 1 depth image"].append(
            (f"5 objects (seed {seed})", arrays["depth"].size, _inputs(arrays, True))
        )
    points, _, viewpoints = load_points(data_path("mug.pcd"))
    kinds["mug.pcd"] = [("data/mug.pcd", len(points), {"cloud": np.asarray(points), "viewpoints": viewpoints})]
    return kinds


# -- timing


def time_synthesis(model, inputs: dict, repeats: int, seed: int, **changes) -> tuple[dict, object]:
    """{stage: [seconds per repeat]} (GraspSet.timing's stages and "whole", the perf_counter around the call)
    after one warm-up call, on synthesize's input keywords; and the last GraspSet."""
    opts = graspmix.SynthesisOptions().updated({"seed": seed, **changes})
    model.synthesize(options=opts, target="largest", **inputs)
    times: dict[str, list[float]] = {}
    grasps = None
    for _ in range(repeats):
        t0 = time.perf_counter()
        grasps = model.synthesize(options=opts, target="largest", **inputs)
        whole = time.perf_counter() - t0
        timing = dict(grasps.timing)
        if "total" in timing:
            timing["outside"] = whole - timing["total"]
        timing.update(segmentation_steps(grasps, timing))
        for stage, t in {**timing, "whole": whole}.items():
            times.setdefault(stage, []).append(float(t))
    return times, grasps


# The segmentation's own steps (Segmentation.step_seconds), printed under it: "seg:completion" is what the
# segmentation stage spends beyond them (the completion of every object and the choice of targets).
SEGMENTATION_STEPS = {"voxel": "voxel", "visibility": "visibility", "outliers": "outliers", "clusters": "clusters"}


def segmentation_steps(grasps, timing: dict) -> dict:
    """{"seg:<step>": s} of the GraspSet's scene: its voxel grid, visibility model, outliers and clusters, the
    other rules summed ("seg:rules": plane candidates, table cut, merge, join, split, objects) and the completion
    with the targets ("seg:completion"); {} without a scene."""
    scene = getattr(grasps, "scene", None)
    if scene is None or "segmentation" not in timing:
        return {}
    steps = dict(scene.result.step_seconds)
    out = {f"seg:{name}": steps.pop(key, 0.0) for key, name in SEGMENTATION_STEPS.items()}
    out["seg:rules"] = sum(steps.values())
    out["seg:completion"] = max(0.0, timing["segmentation"] - float(scene.result.seconds))
    return out


def p90(values) -> float:
    return float(np.percentile(values, 90))


def stage_names(times: dict) -> list[str]:
    """STAGES in order (the segmentation's steps under it), any other stage the GraspSet reports after them, then
    "whole"."""
    steps = [s for s in times if s.startswith("seg:")]
    extra = sorted(s for s in times if s not in STAGES and s != "whole" and s not in steps)
    out = []
    for s in STAGES:
        if s in times:
            out += [s] + (steps if s == "segmentation" else [])
    return out + extra + ["whole"]


def print_kind(kind: str, per_method: dict, counts: list[str]) -> None:
    """One scene kind: median and p90 (over all its clouds and repeats) per stage and method, KDE/GMM."""
    print(f"\n## {kind}: {'; '.join(counts)}")
    print(f"{'stage':<14} {'GMM med':>9} {'GMM p90':>9} {'KDE med':>9} {'KDE p90':>9} {'KDE/GMM':>8}   (ms)")
    for s in stage_names(per_method["gmm"]):
        g, k = per_method["gmm"].get(s, []), per_method["kde"].get(s, [])
        if not g or not k:
            continue
        mg, mk = statistics.median(g), statistics.median(k)
        ratio = f"{mk / mg:8.2f}" if mg > 0 else f"{'-':>8}"
        print(f"{s:<14} {mg * 1e3:9.1f} {p90(g) * 1e3:9.1f} {mk * 1e3:9.1f} {p90(k) * 1e3:9.1f} {ratio}")


def bench_scenes(models: dict, kinds: dict, args) -> dict:
    """Times both methods on every cloud; prints each kind; returns {kind: {method: {stage: [s]}}}."""
    results = {}
    for kind, clouds in kinds.items():
        per_method = {m: {} for m in models}
        counts = []
        for name, n_raw, inputs in clouds:
            surface = {}
            for method, model in models.items():
                times, grasps = time_synthesis(model, inputs, args.repeats, args.seed)
                for s, v in times.items():
                    per_method[method].setdefault(s, []).extend(v)
                surface[method] = (len(grasps.surface.points), len(grasps.grasps))
            counts.append(
                f"{name} {n_raw} raw / {surface['gmm'][0]} surface pts, {surface['gmm'][1]}/{surface['kde'][1]} grasps"
            )
        print_kind(kind, per_method, counts)
        results[kind] = per_method
    return results


def print_summary(results: dict) -> None:
    """Whole-call medians per kind against issue 15's targets."""
    print("\n## whole call (perf_counter), median per scene kind (issue 15 targets: GMM < 20 ms single object,")
    print("## < 40 ms for 5 objects; KDE/GMM >= 5)")
    print(f"{'scene kind':<26} {'GMM (ms)':>9} {'KDE (ms)':>9} {'KDE/GMM':>8}")
    for kind, per_method in results.items():
        mg, mk = (statistics.median(per_method[m]["whole"]) for m in METHODS)
        print(f"{kind:<26} {mg * 1e3:9.1f} {mk * 1e3:9.1f} {mk / mg:8.2f}")


# -- processes


def _wall(cmd: list[str], n: int, cwd: str) -> tuple[list[float], int]:
    """Wall times of n runs of cmd (a subprocess each, after one run not timed) and the last return code.
    The runs may write bytecode (PYTHONDONTWRITEBYTECODE dropped): an installed package has its .pyc files
    (pip compiles them), and a source tree without them would compile every module on every start."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    walls, rc = [], 0
    for i in range(n + 1):
        t0 = time.perf_counter()
        rc = subprocess.run(cmd, cwd=cwd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode
        if i > 0:
            walls.append(time.perf_counter() - t0)
    return walls, rc


def _cli_command() -> list[str]:
    """The graspmix_cli entry point beside this interpreter (not a shell shim in front of it), else -m."""
    script = Path(sys.executable).parent / "graspmix_cli"
    return [str(script)] if script.exists() else [sys.executable, "-m", "graspmix.cli"]


def bench_processes(n: int) -> None:
    mug = str(data_path("mug.pcd"))
    print(
        f"\n## processes (median of {n} runs after one untimed, wall time; this interpreter's environment, "
        "PYTHONPATH included, bytecode caching on)"
    )
    with tempfile.TemporaryDirectory() as tmp:
        cli = _cli_command()
        walls, rc = _wall([*cli, "synthesize", "--cloud", mug, "--out", "grasps.json"], n, tmp)
        print(
            f"graspmix_cli synthesize --cloud data/mug.pcd  median {statistics.median(walls) * 1e3:7.0f} ms "
            f"(min {min(walls) * 1e3:.0f}, max {max(walls) * 1e3:.0f}; exit {rc}; target < 250 ms)"
        )
        packed = str(data_path("scenes", "packed4.pcd"))  # one camera's organized view with its pose: the image path
        walls, rc = _wall([*cli, "synthesize", "--cloud", packed, "--target", "largest", "--out", "g.json"], n, tmp)
        print(
            f"graspmix_cli synthesize --cloud data/scenes/packed4.pcd (organized) --target largest  median "
            f"{statistics.median(walls) * 1e3:7.0f} ms (min {min(walls) * 1e3:.0f}, max {max(walls) * 1e3:.0f}; "
            f"exit {rc}; issue 26's target < 300 ms)"
        )
        walls, rc = _wall([sys.executable, "-c", "import graspmix"], n, tmp)
        print(
            f'python -c "import graspmix"                   median {statistics.median(walls) * 1e3:7.0f} ms '
            f"(min {min(walls) * 1e3:.0f}, max {max(walls) * 1e3:.0f}; exit {rc})"
        )
        walls, rc = _wall([sys.executable, "-c", "pass"], n, tmp)
        print(f'python -c "pass"                               median {statistics.median(walls) * 1e3:7.0f} ms')
        own = []  # the self time -X importtime gives graspmix._core: the loading of its shared libraries
        for _ in range(n):
            err = subprocess.run(
                [sys.executable, "-X", "importtime", "-c", "import graspmix._core"],
                cwd=tmp,
                capture_output=True,
                text=True,
            ).stderr
            own += [
                int(ln.split("|")[0].split(":")[1]) * 1e-6 for ln in err.splitlines() if ln.endswith(" graspmix._core")
            ]
        print(f"import graspmix._core (-X importtime, self)    median {statistics.median(own) * 1e3:7.1f} ms")


def organised_view(path: Path, width: int = 640, height: int = 480, seed: int = 0) -> int:
    """A depth camera's organised cloud as a binary PCD written by numpy (x right, y down, z forward): a table
    tilted away and a ball on it, a seeded 15 % of the pixels NaN (no return). Returns the finite points."""
    v, u = np.mgrid[0:height, 0:width].astype(np.float64)
    fx = fy = 525.0
    rx, ry = (u - width / 2) / fx, (v - height / 2) / fy
    z = 1.2 - 0.4 * (v / height)
    ball = (u - width / 2) ** 2 + (v - height / 2) ** 2 < 80.0**2
    z[ball] -= 0.05 * np.sqrt(1 - ((u[ball] - width / 2) ** 2 + (v[ball] - height / 2) ** 2) / 80.0**2)
    xyz = np.stack([rx * z, ry * z, z], axis=-1).astype(np.float32)
    xyz[np.random.default_rng(seed).random((height, width)) < 0.15] = np.nan
    head = (
        f"VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH {width}\nHEIGHT {height}\n"
        f"VIEWPOINT 0 0 0 1 0 0 0\nPOINTS {width * height}\nDATA binary\n"
    )
    path.write_bytes(head.encode() + xyz.tobytes())
    return int(np.isfinite(xyz).all(axis=-1).sum())


def bench_cloud_files(repeats: int = 20) -> None:
    print(f"\n## cloud files (load_cloud, median of {repeats} after one untimed)")
    with tempfile.TemporaryDirectory() as tmp:
        binary = Path(tmp) / "view.pcd"
        kept = organised_view(binary)
        c = graspmix.load_cloud(binary)
        compressed = Path(tmp) / "view_lzf.pcd"
        graspmix.save_cloud(
            compressed, c.organized().reshape(-1, 3), encoding="binary_compressed", width=640, height=480
        )
        for label, path in (("binary", binary), ("binary_compressed", compressed)):
            t = median_seconds(lambda p=path: graspmix.load_cloud(p), repeats)
            print(f"640x480 organised PCD, {label:<17}  median {t * 1e3:6.1f} ms ({kept} points kept, pixels too)")


# -- scaling


def print_scaling(label: str, sizes: list[int], rows: list[dict], unit: str) -> None:
    """Per stage: median ms and microseconds per unit at each size; flags a time ratio > GROWTH_FLAG x the size
    ratio, against the first size and against the previous one."""
    stages = stage_names(rows[0])
    print(f"{label:<14}" + "".join(f"{n:>12}" for n in sizes) + "   flag (vs the first and the previous size)")
    for s in stages:
        med = [statistics.median(r.get(s, [0.0])) for r in rows]
        cells = "".join(f"{t * 1e3:>9.1f} ms" for t in med)
        per = "".join(f"{t * 1e6 / n:>9.2f} us" for t, n in zip(med, sizes))
        flags = [
            f"x{med[i] / med[j]:.1f} for x{sizes[i] / sizes[j]:.1f} ({sizes[j]}->{sizes[i]})"
            for i in range(1, len(sizes))
            for j in sorted({0, i - 1})
            if med[j] > 0 and med[i] / med[j] > GROWTH_FLAG * sizes[i] / sizes[j]
        ]
        print(f"{s:<14}{cells}   {'SUPERLINEAR ' + ', '.join(flags) if flags else ''}")
        print(f"{'  per ' + unit:<14}{per}")


def upsampled(points, viewpoints, n: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """The SIZES[0] points nearest (in x, y) the centre of the points 1 cm above the table (the object and
    a ring of table), then jittered copies of them (N(0, JITTER) per coordinate) up to n points."""
    centre = points[points[:, 2] > 0.01, :2].mean(axis=0)
    rows = np.argsort(np.linalg.norm(points[:, :2] - centre, axis=1))[: SIZES[0]]
    base, vp = points[rows], viewpoints[rows]
    rng = np.random.default_rng(seed)
    copies = [base] + [base + rng.normal(0.0, JITTER, base.shape) for _ in range(math.ceil(n / len(base)) - 1)]
    return np.vstack(copies)[:n], np.vstack([vp] * len(copies))[:n]


def bench_scaling(model, args) -> None:
    """The GMM path against the raw cloud size (a crop of the first single-object scene's one-view cloud,
    upsampled by jittered copies) and against n_samples (the whole one-view cloud of that scene)."""
    from graspmix.sim import scenes

    obj = scenes.choose_objects(data_path("objects", "clutter_dev.txt"), 1, args.seed)[0]
    key = f"single-{Path(obj).stem}-s{args.seed}-v1-{'noise' if args.noise else 'clean'}"
    arrays = _cached(
        args.cache, key, lambda: _acquire(scenes.make_scene([obj], "packed", args.seed), 1, args.noise, args.seed)
    )
    scene_points, scene_viewpoints = arrays["points"], arrays["viewpoints"]
    sizes = SIZES[::2] if args.quick else SIZES
    rows, raw, surface = [], [], []
    for n in sizes:
        points, viewpoints = upsampled(scene_points, scene_viewpoints, n, args.seed)
        times, grasps = time_synthesis(model, {"cloud": points, "viewpoints": viewpoints}, args.repeats, args.seed)
        rows.append(times)
        raw.append(len(points))
        surface.append(len(grasps.surface.points))
    print(f"\n## scaling with the raw cloud size (GMM, {obj}, one view, {SIZES[0]} points around the object and")
    print(f"## jittered copies (sigma {JITTER * 1e3:g} mm); surface points after segmentation:")
    print(f"## {', '.join(map(str, surface))})")
    print_scaling("raw points", raw, rows, "raw pt")
    samples = SAMPLES[:2] if args.quick else SAMPLES
    whole = {"cloud": scene_points, "viewpoints": scene_viewpoints}
    rows = [time_synthesis(model, whole, args.repeats, args.seed, **{"sampling.n_samples": n})[0] for n in samples]
    print(f"\n## scaling with n_samples (GMM, the same scene, {len(scene_points)} raw points; n_optimise fixed)")
    print_scaling("n_samples", list(samples), rows, "sample")


# -- main


def machine(label: str) -> str:
    load = ", ".join(f"{v:.2f}" for v in os.getloadavg())
    return f"{label}: load average (1, 5, 15 min) {load}"


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeats", type=int, default=5, help="timed calls per cloud and method (after one warm-up)")
    p.add_argument("--quick", action="store_true", help="one repeat, fewer clouds and sizes (a smoke run)")
    p.add_argument("--seed", type=int, default=0, help="seed of the scenes, the noise and the synthesis")
    p.add_argument("--cache", type=Path, help="folder to keep the rendered clouds in (.npz) between runs")
    p.add_argument("--no-noise", dest="noise", action="store_false", help="render without the depth noise model")
    p.add_argument("--process-runs", type=int, default=5, help="subprocess runs for the CLI and import times")
    args = p.parse_args()
    if args.repeats < 1:
        raise ValueError(f"--repeats must be >= 1, got {args.repeats}")
    if args.quick:
        args.repeats, args.process_runs = 1, 2
    t_start = time.perf_counter()
    affinity = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else "?"
    print(
        f"OMP_NUM_THREADS={os.environ.get('OMP_NUM_THREADS', '(unset)')}  os.cpu_count()={os.cpu_count()}  "
        f"usable cpus={affinity}  repeats={args.repeats}  seed={args.seed}  noise={'on' if args.noise else 'off'}"
    )
    print(machine("start"))
    models = {m: graspmix.GraspModel.load(graspmix.default_model_path(m)) for m in METHODS}
    t0 = time.perf_counter()
    kinds = make_clouds(args)
    print(f"clouds made (or read from the cache) in {time.perf_counter() - t0:.1f} s")
    results = bench_scenes(models, kinds, args)
    print_summary(results)
    bench_processes(args.process_runs)
    bench_cloud_files()
    bench_scaling(models["gmm"], args)
    print()
    print(machine("end"))
    print(f"benchmark wall time {time.perf_counter() - t_start:.0f} s")


if __name__ == "__main__":
    main()
