"""graspmix_cli: the command line over the graspmix library.

Every subcommand turns a bad input into one line on stderr and exit status 2.
"""
from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

import graspmix

DATA = Path(__file__).resolve().parent / "data"


class CliError(Exception):
    """A user error: printed as one line, exit status 2."""


def _cmd_info(args: argparse.Namespace) -> int:
    info = graspmix.build_info()
    info["python"] = sys.version.split()[0]
    info["numpy"] = np.__version__
    width = max(len(k) for k in info)
    for name in ["graspmix", "eigen", "pcl", "fcl", "bullet", "urdfdom", "assimp", "pybind11", "openmp", "python", "numpy"]:
        if name in info:
            print(f"{name:<{width}}  {info[name]}")
    return 0


def _load_array(path: str) -> np.ndarray:
    p = Path(path)
    if not p.is_file():
        raise CliError(f"{path}: no such file")
    try:
        if p.suffix == ".npy":
            data = np.load(p, allow_pickle=False)
        else:
            data = np.loadtxt(p, delimiter="," if p.suffix == ".csv" else None, ndmin=2)
    except (ValueError, OSError) as e:
        raise CliError(f"{path}: cannot read numbers ({e})") from None
    if data.ndim != 2 or data.shape[0] == 0:
        raise CliError(f"{path}: expected a non-empty 2-D array, got shape {data.shape}")
    return np.asarray(data, dtype=float)


def _cmd_fit_gmm(args: argparse.Namespace) -> int:
    X = _load_array(args.data)
    gm = graspmix.GaussianMixture(n_components=args.components, n_init=args.n_init, seed=args.seed,
                                  max_iter=args.max_iter, tol=args.tol)
    t0 = time.perf_counter()
    gm.fit(X)
    dt = time.perf_counter() - t0
    print(f"fitted {args.components} components to {X.shape[0]} x {X.shape[1]} data in {dt * 1e3:.1f} ms: "
          f"converged={gm.converged_} after {gm.n_iter_} iterations, mean log-likelihood {gm.score(X):.4f}")
    for k in range(gm.n_components):
        mean = np.array2string(gm.means_[k], precision=3, suppress_small=True, max_line_width=200)
        print(f"  component {k}: weight {gm.weights_[k]:.3f}  mean {mean}")
    if args.out:
        out = {"format": "graspmix.gmm/1", "weights": gm.weights_.tolist(), "means": gm.means_.tolist(),
               "covariances": gm.covariances_.tolist(), "converged": gm.converged_, "n_iter": gm.n_iter_,
               "lower_bound": gm.lower_bound_}
        Path(args.out).write_text(json.dumps(out, indent=1))
        print(f"wrote {args.out}")
    return 0


def _cmd_features(args: argparse.Namespace) -> int:
    """O(v, r) of a cloud file: outward normals, curvatures [k1, k2] and frames, saved as .npz."""
    t0 = time.perf_counter()
    cloud = graspmix.load_cloud(args.cloud)
    points = cloud.points
    print(f"{args.cloud}: {len(points)} points ({cloud.format}"
          + (f", {cloud.n_invalid} NaN points dropped" if cloud.n_invalid else "") + ")")
    scene = None
    if args.voxel_size > 0 or args.remove_outliers or args.remove_plane or args.crop:
        crop = args.crop or [None] * 6
        scene = graspmix.prepare_cloud(points, crop_min=None if args.crop is None else crop[:3],
                                       crop_max=None if args.crop is None else crop[3:], voxel_size=args.voxel_size,
                                       remove_outliers=args.remove_outliers, remove_plane=args.remove_plane,
                                       seed=args.seed)
        points = scene.points
        print(f"prepared: {scene.n_input} -> {scene.n_output} points"
              + (f", support plane {np.array2string(scene.plane, precision=4)}" if scene.plane_found else ""))
    normals = None
    if args.file_normals:
        if cloud.normals is None:
            raise CliError(f"{args.cloud}: --file-normals given but the file has no normal_x/y/z fields")
        if scene is not None:
            raise CliError("--file-normals cannot be combined with clean-up steps (the points change)")
        normals = cloud.normals
    viewpoints = None
    if args.viewpoint is not None:
        viewpoints = np.asarray(args.viewpoint, dtype=float)
    elif cloud.has_viewpoint and args.orientation in ("auto", "viewpoint"):
        viewpoints = np.asarray(cloud.viewpoint[:3])
    s = graspmix.compute_surface_features(points, args.radius, normals=normals, viewpoints=viewpoints,
                                          min_neighbours=args.min_neighbours, orientation=args.orientation)
    k = s.curvatures
    print(f"features: {len(s)} points kept, {s.n_dropped} dropped (fewer than {args.min_neighbours} neighbours "
          f"within {args.radius} m), normals oriented by {s.orientation}, {s.timings['total'] * 1e3:.0f} ms")
    print(f"  k1 median {np.median(k[:, 0]):.4g} (5-95%: {np.quantile(k[:, 0], 0.05):.4g}-{np.quantile(k[:, 0], 0.95):.4g}),"
          f" k2 median {np.median(k[:, 1]):.4g}; {np.mean(s.isotropic) * 100:.0f}% of frames by the isotropic rule")
    if args.out:
        extra = {"plane": scene.plane if scene is not None and scene.plane_found else np.zeros(0)}
        np.savez_compressed(args.out, points=s.points, normals=s.normals, curvatures=s.curvatures, frames=s.frames,
                            indices=s.indices, neighbours=s.neighbours, isotropic=s.isotropic,
                            frame_ambiguity=s.frame_ambiguity, radius=s.radius, orientation=s.orientation,
                            cloud=str(args.cloud), **extra)
        print(f"wrote {args.out}")
    if args.plot:
        from .plots import plot_surface_features

        plot_surface_features(s, args.plot, title=f"{Path(args.cloud).name}: radius {args.radius} m", normals=args.plot_normals)
        print(f"wrote {args.plot}")
    print(f"total {time.perf_counter() - t0:.2f} s")
    return 0


def _parse_floats(text: str, n: int, what: str) -> np.ndarray:
    try:
        v = np.array([float(x) for x in text.split(",")])
    except ValueError:
        raise CliError(f"{what}: expected {n} comma-separated numbers, got {text!r}") from None
    if v.shape != (n,) or not np.all(np.isfinite(v)):
        raise CliError(f"{what}: expected {n} comma-separated finite numbers, got {text!r}")
    return v


def _parse_joints(text: str, what: str) -> dict:
    out = {}
    for item in text.split(","):
        name, sep, value = item.partition("=")
        if not sep:
            raise CliError(f"{what}: expected name=value[,name=value...], got {text!r}")
        try:
            out[name.strip()] = float(value)
        except ValueError:
            raise CliError(f"{what}: {value!r} is not a number") from None
    return out


def _cmd_demo(args: argparse.Namespace) -> int:
    from .demo import record_demonstration

    wrist = _parse_floats(args.wrist, 7, "--wrist")
    demo = record_demonstration(args.object, args.hand, wrist, _parse_joints(args.pregrasp, "--pregrasp"),
                                _parse_joints(args.close, "--close"), grip_force=args.force, seed=args.seed)
    out = Path(args.out)
    if args.cloud_out:
        graspmix.save_cloud(args.cloud_out, demo.cloud)
        demo.cloud_path = Path(args.cloud_out).resolve()
    demo.save(out)
    joints = ", ".join(f"{k}={v:.4f}" for k, v in demo.grasp_joints.items())
    print(f"demonstration: {len(demo.cloud)} object points, hand stopped at {joints}; wrote {out}")
    return 0


def _cmd_learn(args: argparse.Namespace) -> int:
    t0 = time.perf_counter()
    model = graspmix.learn(args.demo, args.method, n_components=args.components, seed=args.seed,
                           max_distance=args.max_distance)
    model.save(args.out)
    print(f"learnt a {model.method} model in {time.perf_counter() - t0:.2f} s: contact models for "
          + ", ".join(f"{m.link_name} ({m.n_points} points)" for m in model.synthesizer.contact_models))
    print(f"wrote {args.out}")
    return 0


def _print_grasps(grasps, top: int) -> None:
    rows = grasps.grasps[:top]
    if not rows:
        return
    keys = list(rows[0]["experts"].keys())
    short = [k.replace("contact/", "Q:") for k in keys]
    header = f"{'rank':>4} {'log L':>9} " + " ".join(f"{k:>14}" for k in short) + "   wrist position (m)        opening"
    print(header)
    for g in rows:
        terms = " ".join(f"{g['experts'][k]:>14.3f}" for k in keys)
        pos = ", ".join(f"{x:+.3f}" for x in g["T_world_wrist"][:3])
        joints = ", ".join(f"{v:.4f}" for v in g["grasp_joints"].values())
        print(f"{g['rank']:>4} {g['log_likelihood']:>9.3f} {terms}   [{pos}]   {joints}")


def _cmd_synthesize(args: argparse.Namespace) -> int:
    model_path = Path(args.model) if args.model else graspmix.default_model_path(args.method or "gmm")
    model = graspmix.GraspModel.load(model_path)
    if args.method and args.model and model.method != args.method:
        raise CliError(f"--method {args.method} but the model {model_path} is a {model.method} model")
    if args.hand and Path(args.hand).resolve() != model.hand_path.resolve():
        other = graspmix.Hand.from_urdf(args.hand)
        if other.name != model.hand.name or other.link_names != model.hand.link_names:
            raise CliError(f"the model {model_path.name} was learnt for hand '{model.hand.name}', "
                           f"not '{other.name}' ({args.hand})")
    axis = _parse_floats(args.approach_axis, 3, "--approach-axis") if args.approach_axis else None
    grasps = model.synthesize(args.cloud, n_samples=args.samples, n_optimise=args.optimise_top,
                              optimise=not args.no_optimise, seed=args.seed, remove_plane=not args.no_plane,
                              approach_axis=axis, query_samples=args.query_samples)
    t = grasps.timing
    print(f"{model.method} model '{model_path.name}' on {args.cloud}: {len(grasps.surface.points)} surface points, "
          f"support plane {'found' if grasps.plane is not None else 'none'}")
    print(f"time: features {t['features'] * 1e3:.0f} ms, query densities {t['query'] * 1e3:.0f} ms, "
          f"sampling+ranking {t['sampling'] * 1e3:.0f} ms, optimisation {t['optimisation'] * 1e3:.0f} ms, "
          f"total {t['total'] * 1e3:.0f} ms ({grasps.evaluations} grasp evaluations, {grasps.rejected} samples rejected "
          f"by hard constraints)")
    _print_grasps(grasps, args.top)
    grasps.save(args.out)
    print(f"wrote {args.out} ({len(grasps)} grasps, best first)")
    if args.png:
        from .plots import plot_grasps

        plot_grasps(grasps, model.hand, args.png, top=min(args.top, 3))
        print(f"wrote {args.png}")
    return 0


def _cmd_acquire(args: argparse.Namespace) -> int:
    from graspmix import acquisition

    settings = acquisition.AcquisitionSettings(keep=args.keep)
    post = acquisition.clean_up(voxel_size=args.voxel_size, seed=args.seed) if args.clean else None
    t0 = time.perf_counter()
    acq = acquisition.acquire(args.object, noise=args.noise, seed=args.seed, settings=settings, postprocess=post)
    dt = time.perf_counter() - t0
    graspmix.save_cloud(args.out, acq.points)
    print(f"acquired {len(acq.points)} points of {args.object} from {len(acq.cameras)} cameras "
          f"(noise {'on' if args.noise else 'off'}, seed {args.seed}"
          + (", cleaned up" + (", support plane removed" if acq.plane is not None else "") if args.clean else "")
          + f") in {dt * 1e3:.0f} ms; wrote {args.out}")
    if args.picture:
        acquisition.plot_depth_images(acq, args.picture)
        print(f"wrote {args.picture}")
    return 0


def _cmd_execute(args: argparse.Namespace) -> int:
    from graspmix import sim

    overrides = {k: v for k, v in (("grip_force", args.grip_force), ("lift_height", args.lift_height),
                                   ("hold_time", args.hold_time)) if v is not None}
    r = sim.execute_file(args.object, args.grasps, rank=args.rank, hand=args.hand, **overrides)
    if args.json:
        print(json.dumps(dict(sim.result_dict(r), object=args.object, rank=args.rank)))
    else:
        print(f"grasp {args.rank} on {args.object}: {'SUCCESS' if r.success else 'FAILURE'} ({r.reason}); "
              f"object lifted {r.lift_height * 100:.1f} cm, {r.contact_count} contacts; "
              f"{r.steps} steps = {r.simulated_time:.2f} s simulated in {r.wall_time * 1e3:.0f} ms")
    return 0


def _split_list(text: str, what: str, known) -> list[str]:
    items = [x.strip() for x in text.split(",") if x.strip()]
    if not items:
        raise CliError(f"{what}: empty list")
    for x in items:
        if x not in known:
            raise CliError(f"{what}: unknown value {x!r} (known: {', '.join(known)})")
    return items


def _cmd_experiment(args: argparse.Namespace) -> int:
    import shlex

    from graspmix import experiment

    conditions = _split_list(args.conditions, "--conditions", list(experiment.CONDITIONS)) if args.conditions else None
    methods = _split_list(args.methods, "--methods", list(experiment.METHODS)) if args.methods else None
    objects = experiment.read_objects_file(args.objects) if args.objects else None
    if args.jobs < 1:
        raise CliError(f"--jobs must be at least 1, got {args.jobs}")
    protocol = experiment.Protocol.preset(args.preset, objects=objects, trials=args.trials, conditions=conditions,
                                          methods=methods, seed=args.seed, closing=args.closing)
    command = "graspmix_cli " + " ".join(shlex.quote(a) for a in (args.argv or []))
    n = len(protocol.all_attempts())
    print(f"experiment: {len(protocol.objects)} objects x {protocol.trials} trials x conditions "
          f"{','.join(protocol.conditions)} x methods {','.join(protocol.methods)} = {n} attempts; "
          f"{args.jobs} job(s), executor {args.executor}; into {args.out}", flush=True)
    res = experiment.run(protocol, args.out, jobs=args.jobs, executor=args.executor, progress=not args.quiet,
                         ray_address=args.ray_address, command=command)
    print(f"ran {res['ran']} attempts in {res['seconds']:.1f} s ({res['skipped']} already done); "
          f"{res['rows']}/{res['total']} in {Path(args.out) / experiment.CSV_NAME}")
    if res["rows"] > 0:
        _print_findings(Path(args.out))
    return 0


def _print_findings(run_dir: Path) -> None:
    from graspmix import report

    summary = json.loads((run_dir / "summary.json").read_text())
    for row in report.findings_table(summary):
        print("  " + " | ".join(row))
    print(f"wrote {run_dir / 'summary.json'}, {run_dir / 'report.md'}, {run_dir / 'report.html'}")


def _cmd_report(args: argparse.Namespace) -> int:
    from graspmix import report

    report.build_report(args.run)
    _print_findings(Path(args.run))
    return 0


def _cmd_benchmark(args: argparse.Namespace) -> int:
    from graspmix import experiment, sim

    objects = experiment.read_objects_file(args.objects) if args.objects else sim.test_objects()
    if args.limit is not None:
        if args.limit < 1:
            raise CliError(f"--limit must be at least 1, got {args.limit}")
        objects = objects[: args.limit]
    res = experiment.benchmark(objects, args.out, n_samples=args.samples, n_optimise=args.optimise_top,
                               seed=args.seed, progress=not args.quiet)
    print(experiment.format_benchmark(res))
    print(f"GMM is {res['ratio_kde_over_gmm']['total']:.2f}x faster than KDE in total (median over objects)")
    print(f"wrote {Path(args.out) / 'benchmark.json'} and {Path(args.out) / 'benchmark.png'}")
    return 0


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="graspmix_cli", description=__doc__.splitlines()[0])
    p.add_argument("--version", action="version", version=f"graspmix {graspmix.__version__}")
    sub = p.add_subparsers(dest="command", required=True)

    s = sub.add_parser("info", help="versions of graspmix and every linked library")
    s.set_defaults(func=_cmd_info)

    s = sub.add_parser("fit-gmm", help="fit a Gaussian mixture by EM to a data file (.npy, .csv, whitespace text)")
    s.add_argument("--data", default=str(DATA / "examples" / "contacts.npy"),
                   help="(N, d) data; default: the bundled example contact data")
    s.add_argument("-k", "--components", type=int, default=2)
    s.add_argument("--n-init", type=int, default=1)
    s.add_argument("--max-iter", type=int, default=100)
    s.add_argument("--tol", type=float, default=1e-3)
    s.add_argument("--seed", type=int, default=0)
    s.add_argument("--out", help="write the fitted parameters as JSON")
    s.set_defaults(func=_cmd_fit_gmm)

    s = sub.add_parser("features", help="outward normals, principal curvatures [k1, k2] and frames of a cloud (.pcd/.ply/.npy)")
    s.add_argument("--cloud", required=True, help="the object cloud (.pcd, .ply, or .npy (N, 3))")
    s.add_argument("--radius", type=float, default=0.01, help="neighbourhood radius in metres (default 0.01, as the paper)")
    s.add_argument("--out", help="write the features as .npz (points, normals, curvatures, frames, indices, ...)")
    s.add_argument("--plot", help="write a picture of the cloud coloured by k1 and k2 (.png/.pdf/.svg)")
    s.add_argument("--plot-normals", type=int, default=0, metavar="N", help="draw N normals in the picture")
    s.add_argument("--orientation", default="auto", choices=["auto", "viewpoint", "propagate", "centroid", "given"],
                   help="how normals are turned outward (auto: the file's or --viewpoint camera, else propagation)")
    s.add_argument("--viewpoint", type=float, nargs=3, metavar=("X", "Y", "Z"), help="camera position for the normals")
    s.add_argument("--file-normals", action="store_true", help="use the file's normals instead of estimating them")
    s.add_argument("--min-neighbours", type=int, default=10, help="drop points with fewer neighbours within radius")
    s.add_argument("--voxel-size", type=float, default=0.0, help="voxel-grid down-sampling first (m; 0 = off)")
    s.add_argument("--remove-outliers", action="store_true", help="statistical outlier removal first")
    s.add_argument("--remove-plane", action="store_true", help="remove the dominant support plane (RANSAC) first")
    s.add_argument("--crop", type=float, nargs=6, metavar=("XMIN", "YMIN", "ZMIN", "XMAX", "YMAX", "ZMAX"),
                   help="keep only points inside this box first")
    s.add_argument("--seed", type=int, default=0, help="seed of the RANSAC plane search")
    s.set_defaults(func=_cmd_features)
    s = sub.add_parser("demo", help="record a demonstrated grasp in simulation (pybullet) as a demonstration file")
    s.add_argument("--object", default=str(graspmix.data_path("objects", "box.urdf")),
                   help="object URDF (a path, or relative to pybullet_data); default: the bundled box")
    s.add_argument("--hand", default=str(graspmix.data_path("hands", "wsg50.urdf")), help="hand URDF (default: WSG 50)")
    s.add_argument("--wrist", required=True, help="wrist pose x,y,z,qx,qy,qz,qw in the world (m)")
    s.add_argument("--pregrasp", required=True, help="pre-grasp joints name=value,...")
    s.add_argument("--close", required=True, help="joints to close towards, name=value,... (the fingers stop on contact)")
    s.add_argument("--force", type=float, default=20.0, help="motor force limit (N or N m)")
    s.add_argument("--seed", type=int, default=0)
    s.add_argument("--out", required=True, help="demonstration file (.json)")
    s.add_argument("--cloud-out", help="write the object cloud to this PCD and refer to it (default: inline)")
    s.set_defaults(func=_cmd_demo)

    s = sub.add_parser("learn", help="learn contact and configuration models from one demonstration")
    s.add_argument("--demo", default=str(graspmix.data_path("demos", "box_wsg50.json")), help="demonstration file")
    s.add_argument("--method", default="gmm", choices=["gmm", "kde"])
    s.add_argument("--components", type=int, default=2, help="K of the contact mixtures (GMM)")
    s.add_argument("--max-distance", type=float, default=0.01, help="m: object points this close to a link are its contacts")
    s.add_argument("--seed", type=int, default=0)
    s.add_argument("--out", required=True, help="model file (.json)")
    s.set_defaults(func=_cmd_learn)

    s = sub.add_parser("synthesize", help="synthesise, rank and optimise grasps on a cloud")
    s.add_argument("--cloud", required=True, help="the scene or object cloud (.pcd, .ply, .npy)")
    s.add_argument("--model", help="learnt model (.json); default: the bundled box demonstration model of --method")
    s.add_argument("--method", choices=["gmm", "kde"], default=None, help="with no --model: which bundled model (gmm)")
    s.add_argument("--hand", help="hand URDF; must be the model's hand")
    s.add_argument("--samples", type=int, default=200, help="grasps sampled and ranked (200)")
    s.add_argument("--optimise-top", type=int, default=10, help="best grasps optimised by annealing (10)")
    s.add_argument("--no-optimise", action="store_true", help="rank the samples only")
    s.add_argument("--query-samples", type=int, default=500, help="samples per link for the query densities")
    s.add_argument("--approach-axis", help="prefer wrists approaching along this world axis, e.g. 0,0,-1 for top grasps")
    s.add_argument("--no-plane", action="store_true", help="the cloud is the object alone: find no support plane")
    s.add_argument("--seed", type=int, default=0)
    s.add_argument("--top", type=int, default=5, help="grasps to print")
    s.add_argument("--out", default="grasps.json", help="grasps file (default grasps.json)")
    s.add_argument("--png", help="draw the cloud and the best grasps' hands")
    s.set_defaults(func=_cmd_synthesize)

    s = sub.add_parser("acquire", help="a stitched point cloud of an object from 4 simulated depth cameras (pybullet)")
    s.add_argument("--object", required=True, help="object URDF: a path, or relative to pybullet_data (random_urdfs/012/012.urdf)")
    s.add_argument("--noise", action="store_true", help="apply the depth noise model (sigma_p = 1 px, sigma_d = 1 mm)")
    s.add_argument("--seed", type=int, default=0, help="seed of the noise")
    s.add_argument("--keep", choices=["object", "scene"], default="object",
                   help="object: the pixels that see the object (segmentation); scene: the support plane too")
    s.add_argument("--out", required=True, help="output cloud (.pcd)")
    s.add_argument("--picture", help="also save a picture of the depth images (.png)")
    s.add_argument("--clean", action="store_true",
                   help="clean up: voxel grid, outlier removal, and (with --keep scene) support-plane removal")
    s.add_argument("--voxel-size", type=float, default=0.003, help="m, voxel grid of --clean (default 0.003)")
    s.set_defaults(func=_cmd_acquire)

    s = sub.add_parser("execute", help="execute a grasp from grasps.json on an object in Bullet physics")
    s.add_argument("--object", required=True, help="object URDF: a path, or relative to pybullet_data")
    s.add_argument("--grasps", required=True, help="grasps.json (format graspmix.grasps/1)")
    s.add_argument("--rank", type=int, default=1, help="which grasp (1 = the best)")
    s.add_argument("--hand", help="hand URDF (default: the bundled WSG 50)")
    s.add_argument("--grip-force", type=float, help="N (default 40)")
    s.add_argument("--lift-height", type=float, help="m (default 0.2)")
    s.add_argument("--hold-time", type=float, help="s (default 0.5)")
    s.add_argument("--json", action="store_true", help="print the result as JSON")
    s.set_defaults(func=_cmd_execute)

    s = sub.add_parser("experiment", help="the paper's experiment: conditions A-D, GMM vs KDE, success rates, t-tests, runtimes")
    s.add_argument("--out", required=True, help="run folder (e.g. runs/NAME): attempts.csv, protocol.json, summary.json, "
                   "report.md/html; running again into it resumes")
    s.add_argument("--preset", choices=["smoke", "paper"], default="paper",
                   help="paper: the 60 test objects, 10 trials (default); smoke: 3 objects, 2 trials")
    s.add_argument("--objects", help="objects file, one URDF a line (a path, or relative to pybullet_data); default: the preset's")
    s.add_argument("--trials", type=int, help="trials (default: the preset's)")
    s.add_argument("--conditions", help="comma-separated subset of A,B,C,D (default: all)")
    s.add_argument("--methods", help="comma-separated subset of gmm,kde (default: both)")
    s.add_argument("--seed", type=int, default=None, help="base of every derived seed (default 0)")
    s.add_argument("--closing", choices=["full", "learnt"], default=None,
                   help="full (default): the fingers close until they stop on the object, force-limited; learnt: "
                        "the simulation's default target just past the synthesised grasp joints")
    s.add_argument("--jobs", type=int, default=1, help="parallel worker processes (or Ray tasks)")
    s.add_argument("--executor", choices=["local", "ray"], default="local",
                   help="local processes, or a Ray cluster (a local Ray instance unless --ray-address)")
    s.add_argument("--ray-address", help="address of a running Ray cluster (default: start a local one)")
    s.add_argument("--quiet", action="store_true", help="no progress bar")
    s.set_defaults(func=_cmd_experiment)

    s = sub.add_parser("report", help="rebuild summary.json and report.md/html of an experiment folder from its CSV")
    s.add_argument("run", help="the experiment folder")
    s.set_defaults(func=_cmd_report)

    s = sub.add_parser("benchmark", help="the paper's runtime comparison: medians over objects per stage, GMM vs KDE")
    s.add_argument("--objects", help="objects file (default: the 60 test objects)")
    s.add_argument("--limit", type=int, help="only the first N objects")
    s.add_argument("--samples", type=int, default=200, help="grasps sampled per object (200)")
    s.add_argument("--optimise-top", type=int, default=10, help="best grasps annealed (10)")
    s.add_argument("--seed", type=int, default=0)
    s.add_argument("--out", default="benchmark", help="folder for benchmark.json and benchmark.png (default ./benchmark)")
    s.add_argument("--quiet", action="store_true", help="no progress bar")
    s.set_defaults(func=_cmd_benchmark)
    return p


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    args.argv = list(sys.argv[1:] if argv is None else argv)
    try:
        return args.func(args)
    except BrokenPipeError:  # the reader went away (e.g. `| head`): nothing more to say
        sys.stderr.close()
        return 0
    except (CliError, ValueError) as e:
        message = " ".join(str(e).split())  # one line, whatever the exception's text
        print(f"graspmix_cli {args.command}: error: {message}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print(f"\ngraspmix_cli {args.command}: stopped; finished attempts are kept, the same command resumes",
              file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
