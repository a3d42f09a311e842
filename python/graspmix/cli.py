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


def _cmd_acquire(args: argparse.Namespace) -> int:
    from graspmix import acquisition

    settings = acquisition.AcquisitionSettings(keep=args.keep)
    t0 = time.perf_counter()
    acq = acquisition.acquire(args.object, noise=args.noise, seed=args.seed, settings=settings)
    dt = time.perf_counter() - t0
    acquisition.write_pcd(args.out, acq.points)
    print(f"acquired {len(acq.points)} points of {args.object} from {len(acq.cameras)} cameras "
          f"(noise {'on' if args.noise else 'off'}, seed {args.seed}) in {dt * 1e3:.0f} ms; wrote {args.out}")
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

    s = sub.add_parser("acquire", help="a stitched point cloud of an object from 4 simulated depth cameras (pybullet)")
    s.add_argument("--object", required=True, help="object URDF: a path, or relative to pybullet_data (random_urdfs/012/012.urdf)")
    s.add_argument("--noise", action="store_true", help="apply the depth noise model (sigma_p = 1 px, sigma_d = 1 mm)")
    s.add_argument("--seed", type=int, default=0, help="seed of the noise")
    s.add_argument("--keep", choices=["object", "scene"], default="object",
                   help="object: the pixels that see the object (segmentation); scene: the support plane too")
    s.add_argument("--out", required=True, help="output cloud (.pcd)")
    s.add_argument("--picture", help="also save a picture of the depth images (.png)")
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
    return p


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    try:
        return args.func(args)
    except (CliError, ValueError) as e:
        print(f"graspmix_cli {args.command}: error: {e}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
