"""info, fit-gmm, features: the C++ core on files."""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

from .. import _core
from ..io import GMM_FORMAT, data_path, load_array
from ..io.checks import MAX_COMPONENTS, MAX_ITERATIONS, MAX_SAMPLES
from ..model.settings import FeatureScale
from .common import CliError, float_in, given, input_path, int_in, output_file, picture_file, seed


def cmd_info(args: argparse.Namespace) -> int:
    info = _core.build_info()
    info["python"] = sys.version.split()[0]
    info["numpy"] = np.__version__
    width = max(len(k) for k in info)
    for name in [
        "graspmix",
        "eigen",
        "pcl",
        "fcl",
        "bullet",
        "urdfdom",
        "assimp",
        "pybind11",
        "openmp",
        "python",
        "numpy",
    ]:
        if name in info:
            print(f"{name:<{width}}  {info[name]}")
    return 0


def cmd_fit_gmm(args: argparse.Namespace) -> int:
    X = load_array(args.data)
    gm = _core.GaussianMixture(n_components=args.components, seed=args.seed, **given(args, "n_init", "max_iter", "tol"))
    t0 = time.perf_counter()
    gm.fit(X)
    dt = time.perf_counter() - t0
    print(
        f"fitted {args.components} components to {X.shape[0]} x {X.shape[1]} data in {dt * 1e3:.1f} ms: "
        f"converged={gm.converged_} after {gm.n_iter_} iterations, mean log-likelihood {gm.score(X):.4f}"
    )
    for k in range(gm.n_components):
        mean = np.array2string(gm.means_[k], precision=3, suppress_small=True, max_line_width=200)
        print(f"  component {k}: weight {gm.weights_[k]:.3f}  mean {mean}")
    if args.out:
        out = {
            "format": GMM_FORMAT,
            "weights": gm.weights_.tolist(),
            "means": gm.means_.tolist(),
            "covariances": gm.covariances_.tolist(),
            "converged": gm.converged_,
            "n_iter": gm.n_iter_,
            "lower_bound": gm.lower_bound_,
        }
        Path(args.out).write_text(json.dumps(out, indent=1))
        print(f"wrote {args.out}")
    return 0


def _prepared(args, points):
    """(points, CleanupResult or None) after the clean-up steps asked for."""
    if not (args.voxel_size > 0 or args.remove_outliers or args.remove_plane or args.crop):
        return points, None
    crop = args.crop or [None] * 6
    if args.crop is not None and any(lo > hi for lo, hi in zip(crop[:3], crop[3:])):
        raise CliError(f"--crop: each minimum must be at most its maximum, got {' '.join(f'{x:g}' for x in crop)}")
    scene = _core.prepare_cloud(
        points,
        crop_min=None if args.crop is None else crop[:3],
        crop_max=None if args.crop is None else crop[3:],
        voxel_size=args.voxel_size,
        remove_outliers=args.remove_outliers,
        remove_plane=args.remove_plane,
        seed=args.seed,
    )
    print(
        f"prepared: {scene.n_input} -> {scene.n_output} points"
        + (f", support plane {np.array2string(scene.plane, precision=4)}" if scene.plane_found else "")
    )
    return scene.points, scene


def _normals_and_viewpoints(args, cloud, scene):
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
    elif len(cloud.viewpoints) and args.orientation in ("auto", "viewpoint"):  # per point, following the clean-up
        viewpoints = cloud.viewpoints if scene is None else cloud.viewpoints[np.asarray(scene.indices)]
    elif cloud.has_viewpoint and args.orientation in ("auto", "viewpoint"):
        viewpoints = np.asarray(cloud.viewpoint[:3])
    return normals, viewpoints


def _print_features(args, s) -> None:
    k = s.curvatures
    print(
        f"features: {len(s)} points kept, {s.n_dropped} dropped (fewer than {args.min_neighbours} neighbours "
        f"within {args.radius} m), normals oriented by {s.orientation}, {s.timings['total'] * 1e3:.0f} ms"
    )
    print(
        f"  k1 median {np.median(k[:, 0]):.4g} (5-95%: {np.quantile(k[:, 0], 0.05):.4g}-{np.quantile(k[:, 0], 0.95):.4g}),"
        f" k2 median {np.median(k[:, 1]):.4g}; {np.mean(s.isotropic) * 100:.0f}% of frames by the isotropic rule"
    )


def cmd_features(args: argparse.Namespace) -> int:
    """O(v, r) of a cloud file: outward normals, curvatures [k1, k2] and frames, saved as .npz."""
    t0 = time.perf_counter()
    cloud = _core.load_cloud(args.cloud)
    print(
        f"{args.cloud}: {len(cloud.points)} points ({cloud.format}"
        + (f", {cloud.n_invalid} NaN points dropped" if cloud.n_invalid else "")
        + ")"
    )
    points, scene = _prepared(args, cloud.points)
    normals, viewpoints = _normals_and_viewpoints(args, cloud, scene)
    s = _core.compute_surface_features(
        points,
        args.radius,
        normals=normals,
        viewpoints=viewpoints,
        min_neighbours=args.min_neighbours,
        orientation=args.orientation,
    )
    _print_features(args, s)
    if args.out:
        extra = {"plane": scene.plane if scene is not None and scene.plane_found else np.zeros(0)}
        np.savez_compressed(
            args.out,
            points=s.points,
            normals=s.normals,
            curvatures=s.curvatures,
            frames=s.frames,
            indices=s.indices,
            neighbours=s.neighbours,
            isotropic=s.isotropic,
            frame_ambiguity=s.frame_ambiguity,
            radius=s.radius,
            orientation=s.orientation,
            cloud=str(args.cloud),
            **extra,
        )
        print(f"wrote {args.out}")
    if args.plot:
        from ..viz import plot_surface_features

        plot_surface_features(
            s, args.plot, title=f"{Path(args.cloud).name}: radius {args.radius} m", normals=args.plot_normals
        )
        print(f"wrote {args.plot}")
    print(f"total {time.perf_counter() - t0:.2f} s")
    return 0


COMMANDS = ("info", "fit-gmm", "features")


def add_parsers(sub) -> None:
    s = sub.add_parser("info", help="versions of graspmix and every linked library")
    s.set_defaults(func=cmd_info)

    s = sub.add_parser("fit-gmm", help="fit a Gaussian mixture by EM to a data file (.npy, .csv, whitespace text)")
    s.add_argument(
        "--data",
        type=input_path,
        default=str(data_path("examples", "contacts.npy")),
        help="(N, d) data; default: the bundled example contact data",
    )
    s.add_argument("-k", "--components", type=int_in(1, MAX_COMPONENTS), default=2)
    s.add_argument("--n-init", type=int_in(1, MAX_COMPONENTS), help="initialisations (default: GaussianMixture's, 1)")
    s.add_argument("--max-iter", type=int_in(1, MAX_ITERATIONS), help="EM iterations (default: GaussianMixture's, 100)")
    s.add_argument("--tol", type=float_in(0.0), help="convergence tolerance (default: GaussianMixture's, 1e-3)")
    s.add_argument("--seed", type=seed, default=0)
    s.add_argument("--out", type=output_file, help="write the fitted parameters as JSON")
    s.set_defaults(func=cmd_fit_gmm)

    s = sub.add_parser(
        "features", help="outward normals, principal curvatures [k1, k2] and frames of a cloud (.pcd/.ply/.npy)"
    )
    s.add_argument("--cloud", type=input_path, required=True, help="the object cloud (.pcd, .ply, or .npy (N, 3))")
    s.add_argument(
        "--radius",
        type=float_in(gt=0.0),
        default=FeatureScale.radius,
        help=f"neighbourhood radius in metres (default {FeatureScale.radius}, as the paper)",
    )
    s.add_argument(
        "--out", type=output_file, help="write the features as .npz (points, normals, curvatures, frames, indices, ...)"
    )
    s.add_argument(
        "--plot", type=picture_file, help="write a picture of the cloud coloured by k1 and k2 (.png/.pdf/.svg)"
    )
    s.add_argument(
        "--plot-normals", type=int_in(0, MAX_SAMPLES), default=0, metavar="N", help="draw N normals in the picture"
    )
    s.add_argument(
        "--orientation",
        default="auto",
        choices=["auto", "viewpoint", "propagate", "centroid", "given"],
        help="how normals are turned outward (auto: --viewpoint, else the file's camera(s), else propagation)",
    )
    s.add_argument(
        "--viewpoint", type=float_in(), nargs=3, metavar=("X", "Y", "Z"), help="camera position for the normals"
    )
    s.add_argument("--file-normals", action="store_true", help="use the file's normals instead of estimating them")
    s.add_argument(
        "--min-neighbours",
        type=int_in(0),
        default=_core.SurfaceFeatureSettings().min_neighbours,
        help="drop points with fewer neighbours within radius",
    )
    s.add_argument("--voxel-size", type=float_in(0.0), default=0.0, help="voxel-grid down-sampling first (m; 0 = off)")
    s.add_argument("--remove-outliers", action="store_true", help="statistical outlier removal first")
    s.add_argument("--remove-plane", action="store_true", help="remove the dominant support plane (RANSAC) first")
    s.add_argument(
        "--crop",
        type=float_in(),
        nargs=6,
        metavar=("XMIN", "YMIN", "ZMIN", "XMAX", "YMAX", "ZMAX"),
        help="keep only points inside this box first",
    )
    s.add_argument("--seed", type=seed, default=0, help="seed of the RANSAC plane search")
    s.set_defaults(func=cmd_features)
