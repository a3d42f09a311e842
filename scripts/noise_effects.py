"""What depth noise does inside the pipeline (issue 16): per noise setting (clean, lateral only, depth only,
full) and method (GMM, KDE), the query cloud's curvature features, the spread of M_i(r) over its points, the
query densities' spread and the M_i(r)-weighted frame jitter, over the test objects and trials acquired as the
experiment acquires them (graspmix.experiment.noise_effects).

    python scripts/noise_effects.py --out results/noise-study/effects [--objects FILE] [--trials 2] [--seed 0]

Writes OUT/effects.json and OUT/features.png, jitter.png, measures.png; prints a table; progress on stderr.
"""

import argparse
import sys
import time

from graspmix.experiment import noise_effects as ne
from graspmix.experiment.noise_effects_report import table, write_outputs
from graspmix.experiment.progress import Progress
from graspmix.experiment.protocol import Protocol
from graspmix.io import git_commit, package_version, test_objects
from graspmix.model import GraspModel, default_model_path
from graspmix.model.settings import METHODS


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--objects", help="object list (default: the 60 test objects, data/objects/test60.txt)")
    ap.add_argument("--trials", type=int, default=2, help="trials per object (default 2)")
    ap.add_argument("--seed", type=int, default=0, help="the protocol's base seed (default 0, the experiment's)")
    ap.add_argument("--out", required=True, help="output folder")
    a = ap.parse_args(argv)
    try:
        p = Protocol(objects=test_objects(a.objects), trials=a.trials, seed=a.seed)
        p.check_inputs()
        models = {m: GraspModel.load(default_model_path(m)) for m in METHODS}
        demo = ne.demonstration_contacts(models["gmm"])
        bar = Progress(len(p.objects) * p.trials * len(ne.NOISE_SETTINGS), unit="units")
        t0 = time.perf_counter()
        result = ne.run_study(p, models, progress=bar.update)
        bar.close()
        prov = {
            "graspmix": package_version(),
            "commit": git_commit(),
            "command": "python scripts/noise_effects.py " + " ".join(argv if argv is not None else sys.argv[1:]),
            "objects": len(p.objects),
            "trials": p.trials,
            "seed": p.seed,
            "seconds": round(time.perf_counter() - t0, 1),
        }
        write_outputs(result, demo, a.out, prov)
    except ValueError as e:
        print(f"noise_effects: {e}", file=sys.stderr)
        return 2
    print(table(result))
    return 0


if __name__ == "__main__":
    sys.exit(main())
