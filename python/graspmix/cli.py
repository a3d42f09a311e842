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
