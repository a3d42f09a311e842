"""The public Python entry points with bad values of each class: integers out of range or not integers
(seed=1.5, 2**63), numbers not finite, unwritable save paths, missing or unnamable files, malformed arrays,
an unfitted GaussianMixture. Cases that call no C++ file reader on the bad value share a subprocess."""

from __future__ import annotations

from cases import BOX_URDF, DATA, api, dumps, grasps_doc

MODEL = "m = graspmix.GraspModel.load(graspmix.model.default_model_path('gmm'))\n"
OPTS = "m.synthesize('{data}/mug.pcd', graspmix.SynthesisOptions().updated("  # + changes + ")"
DEMO = str(DATA / "demos" / "box_wsg50.json")
GRASPS = {"grasps.json": dumps(grasps_doc())}


def _group(prefix: str, group: str, cases: dict, setup: str = "", files=None):
    """{label: (code, names)} -> API cases of one group."""
    return [
        api(f"api/{prefix}/{label}", setup + code, names=names, files=files, group=group)
        for label, (code, names) in cases.items()
    ]


def synthesize_cases():
    bad = {
        "seed=1.5": (f"{OPTS}{{'seed': 1.5}}))", ("seed",)),
        "seed=2p63": (f"{OPTS}{{'seed': 2**63}}))", ("seed",)),
        "seed=-1": (f"{OPTS}{{'seed': -1}}))", ("seed",)),
        "seed=True": ("graspmix.SynthesisOptions(seed=True)", ("seed",)),
        "n_samples=3e9": (f"{OPTS}{{'sampling.n_samples': 3 * 10**9}}))", ("sampling.n_samples",)),
        "n_samples=0": (f"{OPTS}{{'sampling.n_samples': 0}}))", ("sampling.n_samples",)),
        "n_optimise=-1": (f"{OPTS}{{'sampling.n_optimise': -1}}))", ("sampling.n_optimise",)),
        "query_samples=1.5": (f"{OPTS}{{'query.n_samples': 1.5}}))", ("query.n_samples",)),
        "concentration=nan": (f"{OPTS}{{'axis_alignment.concentration': float('nan')}}))", ("concentration",)),
        "collision_beta=inf": (f"{OPTS}{{'collision.beta': float('inf')}}))", ("collision.beta",)),
        "options=dict": ("m.synthesize('{data}/mug.pcd', {'n_samples': 5})", ("options",)),
        "options-part=int": ("graspmix.SynthesisOptions(sampling=5)", ("sampling",)),
        "option=unknown": (f"{OPTS}{{'annealing.bogus': 1}}))", ("bogus",)),
        "option-part=unknown": (f"{OPTS}{{'bogus': 1}}))", ("bogus",)),
        "cloud=ragged": ("m.synthesize([[0, 0, 0], [1, 2]])", ("cloud",)),
        "cloud=empty": ("import numpy as np; m.synthesize(np.zeros((0, 3)))", ("cloud",)),
        "cloud=2-columns": ("import numpy as np; m.synthesize(np.zeros((5, 2)))", ("cloud",)),
        "cloud=name-too-long": ("m.synthesize('" + "c" * 300 + ".pcd')", ("255",)),
        "cloud=not-utf8": ("m.synthesize('\\udcff.pcd')", ("UTF-8",)),
        "cloud=missing": ("m.synthesize('absent.pcd')", ("absent.pcd",)),
        "plane=zero-normal": ("m.synthesize('{data}/mug.pcd', plane=[0, 0, 0, 1])", ("plane",)),
        "save=missing-folder": ("m.save('nowhere/m.json')", ("nowhere",)),
        "save=a-folder": ("m.save('.')", ("folder",)),
    }
    return _group("synthesize", "model", bad, MODEL)


def learn_cases():
    bad = {
        "seed=1.5": (f"graspmix.learn('{DEMO}', seed=1.5)", ("seed",)),
        "seed=2p63": (f"graspmix.learn('{DEMO}', seed=2**63)", ("seed",)),
        "n_components=0": (f"graspmix.learn('{DEMO}', n_components=0)", ("n_components",)),
        "n_components=2p40": (f"graspmix.learn('{DEMO}', n_components=2**40)", ("n_components",)),
        "radius=nan": (f"graspmix.learn('{DEMO}', radius=float('nan'))", ("radius",)),
        "voxel_size=-1": (f"graspmix.learn('{DEMO}', voxel_size=-1)", ("voxel_size",)),
        "max_distance=inf": (f"graspmix.learn('{DEMO}', max_distance=float('inf'))", ("max_distance",)),
        "min_points=True": (f"graspmix.learn('{DEMO}', min_points=True)", ("min_points",)),
        "kde_feature_bandwidth=str": (
            f"graspmix.learn('{DEMO}', 'kde', kde_feature_bandwidth='0.1')",
            ("kde_feature_bandwidth",),
        ),
        "config=list": (f"graspmix.learn('{DEMO}', config=[1])", ("config",)),
        "method=svm": (f"graspmix.learn('{DEMO}', 'svm')", ("method",)),
        "demo=missing": ("graspmix.learn('absent.json')", ("absent.json",)),
        "demo=a-folder": ("graspmix.learn('.')", ("folder",)),
        "demo=name-too-long": ("graspmix.learn('" + "d" * 300 + ".json')", ("255",)),
        "load=not-utf8": ("graspmix.GraspModel.load('\\udcff.json')", ("UTF-8",)),
        "load=missing": ("graspmix.GraspModel.load('absent.json')", ("absent.json",)),
        "demo-load=bytes-not-utf8": ("graspmix.Demonstration.load(b'\\xff.json')", ("UTF-8",)),
        "demo-load=number": ("graspmix.Demonstration.load(5)", ("path",)),
    }
    return _group("learn", "learn", bad)


def grasps_cases():
    setup = "from graspmix.model import load_grasps, grasp_by_rank, GraspSet\nfrom pathlib import Path\n"
    bad = {
        "rank=1.5": ("grasp_by_rank(load_grasps('grasps.json'), 1.5)", ("rank",)),
        "rank=0": ("grasp_by_rank(load_grasps('grasps.json'), 0)", ("rank",)),
        "save=missing-folder": ("GraspSet([], Path('h.urdf'), 'gmm', 'c', {}).save('nowhere/g.json')", ("nowhere",)),
        "save=a-folder": ("GraspSet([], Path('h.urdf'), 'gmm', 'c', {}).save('.')", ("folder",)),
        "load=missing": ("load_grasps('absent.json')", ("absent.json",)),
    }
    cases = _group("grasps", "grasps", bad, setup, files=GRASPS)
    cases.append(
        api(
            "api/grasps/ok-load-and-rank-2",
            setup + "assert grasp_by_rank(load_grasps('grasps.json'), 2).log_likelihood == float('-inf')",
            files=GRASPS,
            expect="ok",
            group="grasps",
        )
    )
    return cases


def sim_cases():
    bad = {
        "hold_time=1e7": (
            f"graspmix.sim.execute('{BOX_URDF}', T_world_wrist=[0,0,.2,1,0,0,0], "
            "pregrasp_joints={'finger_left_joint': .05}, grasp_joints={'finger_left_joint': .02}, "
            "hold_time=1e7)",
            ("hold_time",),
        ),
        "close_time=nan": ("graspmix.sim.make_settings(close_time=float('nan'))", ("close_time",)),
        "time_step=1e-9": ("graspmix.sim.make_settings(time_step=1e-9)", ("time_step",)),
        "lift_height=1e6": ("graspmix.sim.make_settings(lift_height=1e6)", ("lift_height",)),
        "solver_iterations=1.5": ("graspmix.sim.make_settings(solver_iterations=1.5)", ("solver_iterations",)),
        "grip_force=str": ("graspmix.sim.make_settings(grip_force='strong')", ("grip_force",)),
        "gravity=2": ("graspmix.sim.make_settings(gravity=[0, 0])", ("gravity",)),
        "rank=1.5": (f"graspmix.sim.execute_file('{BOX_URDF}', 'grasps.json', rank=1.5)", ("rank",)),
        "rank=2p63": (f"graspmix.sim.execute_file('{BOX_URDF}', 'grasps.json', rank=2**63)", ("rank",)),
        "object=name-too-long": ("graspmix.sim.execute_file('" + "o" * 300 + ".urdf', 'grasps.json')", ("255",)),
        "acquire-seed=1.5": (f"graspmix.sim.acquisition.acquire('{BOX_URDF}', seed=1.5)", ("seed",)),
        "acquire-seed=2p63": (f"graspmix.sim.acquisition.acquire('{BOX_URDF}', seed=2**63)", ("seed",)),
        "acquire-width=1e6": (
            "from graspmix.sim import acquisition as a\n"
            f"a.acquire('{BOX_URDF}', settings=a.AcquisitionSettings(cameras=a.ring_cameras(1, "
            "width=10**6)))",
            ("width",),
        ),
        "acquire-scale=nan": (
            "from graspmix.sim import acquisition as a\n"
            f"a.acquire('{BOX_URDF}', settings=a.AcquisitionSettings(object_scale=float('nan')))",
            ("object_scale",),
        ),
        "clean_up-voxel=nan": ("graspmix.sim.acquisition.clean_up(voxel_size=float('nan'))", ("voxel_size",)),
        "demo-grip_force=nan": (
            "from graspmix.sim.demonstration import record_demonstration as r\n"
            f"r('{BOX_URDF}', '{{data}}/hands/wsg50.urdf', [0,0,.2185,1,0,0,0], "
            "{'finger_left_joint': .05}, {'finger_left_joint': 0}, grip_force=float('nan'))",
            ("grip_force",),
        ),
    }
    return _group("sim", "sim", bad, files=GRASPS)


PROTOCOL_OPTS = "ex.Protocol(objects=objs, synthesis=graspmix.SynthesisOptions().updated("  # + changes + "))"


def experiment_cases():
    setup = "from graspmix import experiment as ex\nobjs = graspmix.io.test_objects()[:1]\n"
    bad = {
        "trials=1.5": ("ex.Protocol(objects=objs, trials=1.5)", ("trials",)),
        "trials=True": ("ex.Protocol(objects=objs, trials=True)", ("trials",)),
        "seed=2p63": ("ex.Protocol(objects=objs, seed=2**63)", ("seed",)),
        "synthesis=dict": ("ex.Protocol(objects=objs, synthesis={'n_samples': '10'})", ("synthesis",)),
        "n_optimise=1.5": (f"{PROTOCOL_OPTS}{{'sampling.n_optimise': 1.5}}))", ("n_optimise",)),
        "initial_temperature=nan": (
            f"{PROTOCOL_OPTS}{{'annealing.initial_temperature': float('nan')}}))",
            ("initial_temperature",),
        ),
        "objects=numbers": ("ex.Protocol(objects=[1, 2])", ("objects",)),
        "objects=string": ("ex.Protocol(objects='abc')", ("objects",)),
        "conditions=unhashable": ("ex.Protocol(objects=objs, conditions=[['A']])", ("condition",)),
        "models=list": ("ex.Protocol(objects=objs, models=['gmm'])", ("models",)),
        "run-out=under-a-file": (
            "open('file', 'w').write('x')\nex.run(ex.Protocol(objects=objs, trials=1), 'file/run', progress=False)",
            ("file",),
        ),
        "run-jobs=1.5": ("ex.run(ex.Protocol(objects=objs, trials=1), 'run', jobs=1.5, progress=False)", ("jobs",)),
        "report=missing": ("from graspmix.experiment.report import build_report\nbuild_report('norun')", ("norun",)),
        "benchmark-out=under-a-file": (
            "open('file', 'w').write('x')\nex.benchmark(objs, 'file/b', progress=False)",
            ("file",),
        ),
    }
    return _group("experiment", "experiment", bad, setup)


def gmm_cases():
    """graspmix.GaussianMixture is the C++ class itself: these reach the bindings."""
    return [
        api(
            "api/gmm/unfitted-score",
            "import numpy as np\ngraspmix.GaussianMixture(n_components=2).score(np.zeros((3, 2)))",
            names=("not fitted",),
        ),
        api(
            "api/gmm/seed=1.5",
            "graspmix.GaussianMixture(n_components=2, seed=1.5)",
            names=("seed",),
        ),
        api(
            "api/gmm/seed=2p63",
            "graspmix.GaussianMixture(n_components=2, seed=2**63)",
            names=("seed",),
        ),
    ]


# Fitted densities of each kind: a GaussianMixture, the bundled models' PoseMixture (GMM) and PoseKDE.
DENSITIES = (
    "import numpy as np\n"
    "gm = graspmix.GaussianMixture(n_components=1, seed=0).fit(np.random.default_rng(0).normal(size=(40, 2)))\n"
    "pm, kde = (graspmix.GraspModel.load(graspmix.default_model_path(m)).synthesizer.contact_models[0].density\n"
    "           for m in ('gmm', 'kde'))\n"
)


def density_cases():
    """Sample counts beyond what memory holds, and pickling, on every density class."""
    bad = {
        "gmm-sample=1e12": ("gm.sample(10**12)", ("sample: n", "10000000")),
        "pose-mixture-sample=1e12": ("pm.sample(10**12, np.zeros(pm.n_features))", ("sample: n", "10000000")),
        "pose-kde-sample=1e12": ("kde.sample(10**12, np.zeros(kde.n_features))", ("sample: n", "10000000")),
        "gmm-sample=str": ("gm.sample('3')", ("sample: n",)),
        "gmm-sample-seed=2p70": ("gm.sample(3, seed=2**70)", ("seed",)),
    }
    cases = _group("density", "density", bad, DENSITIES)
    ok = {
        # scikit-learn pickles an unfitted estimator; so does graspmix, and it comes back unfitted.
        "ok-pickle-unfitted": "import pickle\n"
        "g = pickle.loads(pickle.dumps(graspmix.GaussianMixture(n_components=3, max_iter=7)))\n"
        "assert (g.settings.n_components, g.settings.max_iter) == (3, 7) and 'not fitted' in repr(g)\n"
        "try:\n    g.sample(2)\nexcept ValueError:\n    pass\nelse:\n    raise AssertionError('fitted')",
        "ok-pickle-fitted": "import pickle\nassert np.array_equal(pickle.loads(pickle.dumps(gm)).means_, gm.means_)",
        "ok-sample-numpy-count": "assert gm.sample(np.int64(3)).shape == (3, 2)",
    }
    cases += [api(f"api/density/{k}", DENSITIES + code, expect="ok", group="density") for k, code in ok.items()]
    return cases


def cloud_cases():
    """File names that are not UTF-8 (bytes, or str with lone surrogates: what Python makes of such bytes) reach
    the file they name; crop bounds that are NaN."""
    pts = "import numpy as np\npts = np.random.default_rng(0).normal(size=(50, 3))\n"
    return [
        api("api/cloud/load=not-utf8-str", "graspmix.load_cloud('\\udcff.pcd')", names=("no such file",)),
        api("api/cloud/load=not-utf8-bytes", "graspmix.load_cloud(b'\\xff.pcd')", names=("no such file",)),
        api(
            "api/cloud/ok-save-and-load-not-utf8",
            pts + "graspmix.save_cloud('\\udcff.pcd', pts)\n"
            "assert np.allclose(graspmix.load_cloud(b'\\xff.pcd').points, pts, atol=1e-6)",
            expect="ok",
        ),
        api("api/cloud/crop_min=nan", pts + "graspmix.prepare_cloud(pts, crop_min=[np.nan, 0, 0])", names=("crop",)),
        api("api/cloud/crop_max=nan", pts + "graspmix.prepare_cloud(pts, crop_max=[0, 0, np.nan])", names=("crop",)),
    ]


def core_cases():
    """The exp map of long rotation vectors: the angle wraps (half-angle convention: scipy's rotation by 2 w), so
    the result is a unit quaternion however long the vector (beyond about 1e16 rad one ulp of the angle exceeds
    2 pi, and only that is asserted); a vector whose length is no double is an error."""
    setup = "import numpy as np\nfrom scipy.spatial.transform import Rotation\n"
    return [
        api(
            "api/core/ok-quat_exp-long-vectors",
            setup + "w = np.random.default_rng(1).normal(size=(40, 3)) * np.repeat([1e3, 1e6], 20)[:, None]\n"
            "ref = Rotation.from_rotvec(2 * w).as_quat()\n"
            "assert np.allclose(np.abs(np.sum(graspmix.quat_exp(w) * ref, axis=1)), 1, atol=1e-8)",
            expect="ok",
            group="core",
        ),
        api(
            "api/core/ok-quat_exp-1e300",
            setup + "w = np.random.default_rng(2).normal(size=(30, 3)) * np.repeat([1e20, 1e150, 1e300], 10)[:, None]\n"
            "q = graspmix.quat_exp(np.r_[w, [[1e300, 0, 0], [-3e300, 4e300, 0]]])\n"
            "assert np.all(np.isfinite(q)) and np.allclose(np.linalg.norm(q, axis=1), 1, atol=1e-12)",
            expect="ok",
            group="core",
        ),
        api(
            "api/core/quat_exp=1.7e308", "graspmix.quat_exp([[1.7e308, 1.7e308, 0]])", names=("quat_exp",), group="core"
        ),
        api("api/core/quat_exp=inf", "graspmix.quat_exp([[float('inf'), 0, 0]])", names=("quat_exp",), group="core"),
    ]


HAND = "hand = graspmix.Hand.from_urdf(str(graspmix.data_path('hands', 'wsg50.urdf')))\nimport numpy as np\n"
WRIST = "[0, 0, .2, 1, 0, 0, 0]"
JOINTS = "{'finger_left_joint': .02}"


def grasp_cases():
    """A cloud spread over kilometres (its index grid would lose the points' places), and grasps that are not a
    Grasp or lack a field, given to the functions that execute one."""
    bad = {
        "collision-cloud=1e30": (
            "graspmix.CollisionExpert(hand, np.r_[np.zeros((10, 3)), [[1e30, 0, 0]]])",
            ("cloud", "span", "1e+30"),
        ),
        "collision-cloud=2e4": ("graspmix.CollisionExpert(hand, [[0, 0, 0], [0, 2e4, 0]])", ("cloud", "span")),
        "execute-grasp=dict-without-pregrasp": (
            f"graspmix.sim.execute('{BOX_URDF}', {{'T_world_wrist': {WRIST}, 'grasp_joints': {JOINTS}}})",
            ("grasp", "dict"),
        ),
        "execute-grasp=list": (f"graspmix.sim.execute('{BOX_URDF}', {WRIST})", ("grasp", "list")),
        "execute-grasp=without-pregrasp": (
            f"graspmix.sim.execute('{BOX_URDF}', graspmix.Grasp({WRIST}, None, {JOINTS}))",
            ("pregrasp_joints",),
        ),
        "execute-grasp=wrist-text": (
            f"graspmix.sim.execute('{BOX_URDF}', graspmix.Grasp('abcdefg', {JOINTS}, {JOINTS}))",
            ("T_world_wrist",),
        ),
        "pybullet-grasp=dict": (
            f"graspmix.sim.execute_pybullet('{BOX_URDF}', {{'T_world_wrist': {WRIST}}})",
            ("grasp", "dict"),
        ),
        "from_dict=without-pregrasp": (
            f"graspmix.Grasp.from_dict({{'T_world_wrist': {WRIST}, 'grasp_joints': {JOINTS}}})",
            ("pregrasp_joints",),
        ),
    }
    return _group("grasp", "grasp", bad, HAND)


def conversion_cases():
    """Integers beyond C++'s and text where a number goes, at the binding layer: a ValueError naming the argument
    or field, never pybind11's TypeError listing C++ signatures."""
    bad = {
        "settings-attribute=2p70": ("graspmix.SegmentationSettings().min_cluster_size = 2**70", ("min_cluster_size",)),
        "settings-attribute=str": ("graspmix.SamplingSettings().n_samples = '10'", ("n_samples",)),
        "settings-attribute=bool-for-number": ("graspmix.SegmentationSettings().voxel_size = True", ("voxel_size",)),
        "settings-keyword=2p70": ("graspmix.SegmentationSettings(min_cluster_size=2**70)", ("min_cluster_size",)),
        "settings-keyword=str": ("graspmix.QuerySettings(n_samples='500')", ("n_samples",)),
        "options-updated=str": ("graspmix.SynthesisOptions().updated({'sampling.n_samples': '10'})", ("n_samples",)),
        "contact_data-link=str": ("graspmix.contact_data(hand, '0', None, None, None, None)", ("link",)),
        "contact_data-link=2p70": ("graspmix.contact_data(hand, 2**70, None, None, None, None)", ("link",)),
        "ContactModel-n_points=2p70": (
            "graspmix.ContactModel(0, 'palm', graspmix.PoseKDE(), n_points=2**70)",
            ("n_points",),
        ),
        "rest_pose-x=str": (f"graspmix.sim.load_object('{BOX_URDF}').rest_pose(x='left')", ("rest_pose: x",)),
    }
    cases = _group("conversion", "conversion", bad, HAND)
    cases.append(
        api(
            "api/conversion/ok-numpy-integers",
            "import numpy as np\ns = graspmix.SamplingSettings()\ns.n_samples = np.int64(10)\n"
            "assert s.n_samples == 10 and graspmix.SamplingSettings(n_samples=np.int32(7)).n_samples == 7",
            expect="ok",
            group="conversion",
        )
    )
    return cases


CASES = (
    synthesize_cases()
    + learn_cases()
    + grasps_cases()
    + sim_cases()
    + experiment_cases()
    + gmm_cases()
    + density_cases()
    + cloud_cases()
    + core_cases()
    + grasp_cases()
    + conversion_cases()
)
