"""Stage times of grasp synthesis, GMM vs KDE, on the same clouds (the paper's Fig. runtime).

    python3 benchmarks/bench_synthesis.py [--repeats 3]

For the bundled mug scene and four pybullet_data objects (acquired by the simulated cameras), both
bundled models synthesise 200 grasps and optimise the top 10 with 100 annealing iterations. Prints
the median over objects (of the median over repeats) of each stage: query density estimation,
sampling and ranking, optimisation; their total; and the KDE/GMM ratio. Feature computation is shared
by both methods and printed apart.
"""

import argparse
import statistics

import graspmix
from graspmix.sim.acquisition import acquire

OBJECTS = ["random_urdfs/012/012.urdf", "random_urdfs/031/031.urdf", "duck_vhacd.urdf", "cube_small.urdf"]
STAGES = ["query", "sampling", "optimisation"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args()
    clouds = {"mug (scene)": (graspmix.data_path("mug.pcd"), {})}
    for name in OBJECTS:
        clouds[name] = (acquire(name).points, {"segmentation.find_plane": False, "plane": [0, 0, 1, 0]})
    models = {m: graspmix.GraspModel.load(graspmix.default_model_path(m)) for m in ("gmm", "kde")}
    per_method = {m: {s: [] for s in STAGES + ["features", "points"]} for m in models}
    for name, (cloud, kw) in clouds.items():
        for method, model in models.items():
            plane = kw.get("plane")
            changes = {k: v for k, v in kw.items() if k != "plane"}
            runs = [
                model.synthesize(cloud, graspmix.SynthesisOptions().updated({**changes, "seed": r}), plane=plane)
                for r in range(args.repeats)
            ]
            for s in STAGES + ["features"]:
                per_method[method][s].append(statistics.median(g.timing[s] for g in runs))
            per_method[method]["points"].append(len(runs[0].surface.points))
        g, k = per_method["gmm"], per_method["kde"]
        tg = sum(g[s][-1] for s in STAGES)
        tk = sum(k[s][-1] for s in STAGES)
        print(
            f"{name:<28} {g['points'][-1]:>5} pts  GMM {tg * 1e3:7.1f} ms  KDE {tk * 1e3:7.1f} ms  ratio {tk / tg:5.2f}"
        )
    print()
    print(f"{'median over objects':<22} {'GMM (ms)':>10} {'KDE (ms)':>10} {'KDE/GMM':>8}")
    totals = {}
    for s in STAGES:
        mg, mk = (statistics.median(per_method[m][s]) for m in ("gmm", "kde"))
        print(f"{s:<22} {mg * 1e3:>10.1f} {mk * 1e3:>10.1f} {mk / mg:>8.2f}")
    for m in models:
        totals[m] = statistics.median(sum(per_method[m][s][i] for s in STAGES) for i in range(len(clouds)))
    print(
        f"{'total of the three':<22} {totals['gmm'] * 1e3:>10.1f} {totals['kde'] * 1e3:>10.1f} "
        f"{totals['kde'] / totals['gmm']:>8.2f}"
    )
    print(f"{'features (shared)':<22} {statistics.median(per_method['gmm']['features']) * 1e3:>10.1f}")
    print("query samples per link: 500; KDE query kernels per link: 500; GMM query components: 5")


if __name__ == "__main__":
    main()
