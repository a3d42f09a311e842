"""The clutter-removal protocol without the simulator: the loop's rules and counts with scripted stages,
the run folder (resume, determinism, 1 vs 2 jobs, report) with a fake round, and bad input."""

import json
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pytest
from graspmix import clutter
from graspmix.clutter.rounds import Plan, Stages, run_scene
from graspmix.experiment.log import AttemptLog, read_rows
from graspmix.experiment.stats import wilson_ci
from graspmix.model import Grasp


# ---- scripted stages ------------------------------------------------------------------------------
@dataclass
class Spec:
    objects: list

    def without(self, i):
        return Spec([o for k, o in enumerate(self.objects) if k != i])


@dataclass
class Result:
    success: bool
    reason: str
    lift_height: float


@dataclass
class Execution:
    result: Result
    lifted: list
    moved: list
    remaining: Spec


@dataclass
class Obs:
    points: np.ndarray
    viewpoints: np.ndarray = field(default_factory=lambda: np.zeros((1, 3)))


def scripted(outcomes):
    """Stages whose attempt k has outcomes[k]: "success" lifts object 0, "two objects lifted" objects 0
    and 1, "synthesis failed" makes the planner raise, anything else leaves the scene as it is."""
    calls = {"n": 0, "seeds": []}

    def observe(spec, seed):
        calls["seeds"].append(seed)
        return Obs(np.zeros((10 * len(spec.objects), 3)))

    def plan(obs, seed):
        if outcomes[calls["n"]] == "synthesis failed":
            calls["n"] += 1
            raise ValueError("no object found above the plane")
        return Plan(Grasp([0, 0, 0, 0, 0, 0, 1], {}, {}), 0, 1)

    def execute(spec, grasp):
        o = outcomes[calls["n"]]
        calls["n"] += 1
        lifted = {"success": [0], "two objects lifted": [0, 1]}.get(o, [])
        remaining = spec
        for _ in lifted:
            remaining = remaining.without(0)
        return Execution(
            Result(o == "success", o, 0.2 if lifted else 0.0), lifted, [0.0] * len(spec.objects), remaining
        )

    return Stages(observe, plan, execute), calls


def seeds(stage, attempt):
    return 1000 * (stage == "synthesis") + attempt


def run(outcomes, n, **kw):
    stages, calls = scripted(outcomes)
    rows = run_scene(Spec(list(range(n))), stages, seeds, **kw)
    return rows, calls


def test_all_successes_clear_the_table():
    rows, _ = run(["success"] * 3, 3)
    assert [r["stop"] for r in rows] == ["", "", "clear"]
    assert [r["before"] for r in rows] == [3, 2, 1] and rows[-1]["after"] == 0
    assert all(r["placed"] == 3 for r in rows)


def test_two_consecutive_failures_end_the_round():
    rows, _ = run(["success", "no contact", "success", "not held", "start in collision", "success"], 5)
    assert len(rows) == 5 and rows[-1]["stop"] == "two failures"
    assert [r["success"] for r in rows] == [1, 0, 1, 0, 0]
    assert rows[-1]["after"] == 3


def test_alternating_failures_reach_the_bound_of_2n_attempts():
    rows, _ = run(["not held", "success"] * 3, 3)
    assert len(rows) == 6 and rows[-1]["stop"] == "clear"


def test_a_synthesis_failure_is_a_failed_attempt_that_ends_the_round():
    rows, calls = run(["success", "synthesis failed", "success"], 4)
    assert len(rows) == 2 and rows[-1]["stop"] == "no grasp"
    last = rows[-1]
    assert last["outcome"] == "synthesis failed" and last["success"] == 0 and last["after"] == 3
    assert "no object found" in last["error"] and last["grasp"] == ""
    assert calls["seeds"] == [0, 1]  # the observation seeds of attempts 0 and 1


def test_two_objects_lifted_is_a_failure_that_removes_both():
    rows, _ = run(["two objects lifted", "success", "not held", "success"], 4)
    assert [r["after"] for r in rows] == [2, 1, 1, 0]
    assert [r["lifted"] for r in rows] == [2, 1, 0, 1]
    assert rows[-1]["stop"] == "clear" and sum(r["success"] for r in rows) == 2


def test_attempt_limit():
    rows, _ = run(["success", "not held"] * 5, 8, max_attempts=3)
    assert len(rows) == 3 and rows[-1]["stop"] == "attempt limit"


def test_a_success_that_removes_nothing_is_an_error():
    stages, _ = scripted(["success"])
    bad = Stages(stages.observe, stages.plan, lambda spec, g: Execution(Result(True, "success", 0.2), [0], [0.0], spec))
    with pytest.raises(RuntimeError, match="no object left the scene"):
        run_scene(Spec([0, 1]), bad, seeds)
    with pytest.raises(ValueError, match="no objects"):
        run_scene(Spec([]), bad, seeds)


# ---- summary counts --------------------------------------------------------------------------------
def rows_of(rounds):
    """CSV-like rows of scripted rounds [(mode, scene, method, outcomes, n)]."""
    out = []
    for mode, scene, method, outcomes, n in rounds:
        for r in run(outcomes, n)[0]:
            r.update(mode=mode, scene=scene, method=method, scene_seed=scene)
            out.append(r)
    return out


PROTO = {"modes": ["pile"], "methods": ["gmm"], "scenes": 2, "objects": 5}


def test_gsr_dr_and_counts():
    rows = rows_of(
        [
            ("pile", 0, "gmm", ["success"] * 5, 5),  # 5/5 attempts, 5/5 removed
            ("pile", 1, "gmm", ["success", "no contact", "not held"], 5),  # 1/3, 1/5
        ]
    )
    s = clutter.summarize(rows, {"protocol": PROTO})
    c = s["results"]["pile"]["gmm"]
    assert c["gsr"]["rate"] == pytest.approx(6 / 8) and c["gsr"]["trials"] == 8
    assert c["dr"]["rate"] == pytest.approx(6 / 10) and c["dr"]["trials"] == 10
    assert c["outcomes"] == {"success": 6, "no contact": 1, "not held": 1}
    assert c["stops"] == {"clear": 1, "two failures": 1}
    assert c["per_scene"]["1"]["gsr"] == pytest.approx(1 / 3) and c["per_scene"]["1"]["remaining"] == 4
    assert s["rounds"] == {"done": 2, "expected": 2, "complete": True}
    # The scenes differ (1.0 vs 0.2 of their objects removed): the DR interval is wider than Wilson's over
    # 10 independent objects.
    lo, hi = wilson_ci(6, 10)
    assert c["dr"]["design_effect"] > 1 and c["dr"]["low"] < lo and c["dr"]["high"] > hi


def test_an_unfinished_round_is_not_counted():
    rows = rows_of([("pile", 0, "gmm", ["success"] * 5, 5), ("pile", 1, "gmm", ["success", "not held", "not held"], 5)])
    s = clutter.summarize(rows[:-1], {"protocol": PROTO})  # the second round's last row lost
    assert s["rounds"]["done"] == 1 and s["results"]["pile"]["gmm"]["gsr"]["trials"] == 5


# ---- stats: Wilson's interval on known values ----------------------------------------------------
Z = 1.959963984540054  # the standard normal's 97.5% quantile


def test_wilson_closed_forms():
    for n in (1, 10, 57):
        lo, hi = wilson_ci(0, n)
        assert lo == pytest.approx(0, abs=1e-12) and hi == pytest.approx(Z * Z / (n + Z * Z), rel=1e-12)
        lo, hi = wilson_ci(n, n)
        assert hi == pytest.approx(1, abs=1e-12) and lo == pytest.approx(n / (n + Z * Z), rel=1e-12)
    # p = 1/2: centre 1/2, half-width z / (2 sqrt(n + z^2)).
    lo, hi = wilson_ci(5, 10)
    half = Z / (2 * math.sqrt(10 + Z * Z))
    assert (lo, hi) == pytest.approx((0.5 - half, 0.5 + half), rel=1e-12)
    assert (lo, hi) == pytest.approx((0.2366, 0.7634), abs=1e-4)
    with pytest.raises(ValueError):
        wilson_ci(3, 2)
    # The interval holds the rate exactly at its ends, whatever the rounding: all of an effective (non-integer)
    # count, as the clutter report's design effect gives (it came to 0.9999999999999999, a negative error bar).
    for n in (84 / 1.7, 13.37, 1e6 / 3):
        assert wilson_ci(n, n)[1] == 1.0 and wilson_ci(0, n)[0] == 0.0
    for k, n in ((1, 3), (7, 9.5), (2, 2.000001)):
        lo, hi = wilson_ci(k, n)
        assert lo <= k / n <= hi


def test_mcnemar_exact_closed_forms():
    from graspmix.experiment.stats import mcnemar_exact

    # Two-sided binomial at 1/2 of the discordant pairs: all k of one side, 2 / 2^k; a tie, 1.
    for k in (1, 5, 12):
        assert mcnemar_exact(0, k) == pytest.approx(min(1.0, 2 * 0.5**k), rel=1e-12)
        assert mcnemar_exact(k, 0) == mcnemar_exact(0, k)
    assert mcnemar_exact(4, 4) == pytest.approx(1.0) and mcnemar_exact(0, 0) == 1.0
    # 1 against 5: P(X <= 1) + P(X >= 5) for X ~ Bin(6, 1/2) = 2 * 7 / 64.
    assert mcnemar_exact(1, 5) == pytest.approx(14 / 64, rel=1e-12)


def test_clustered_rate_design_effect():
    from graspmix.experiment.stats import clustered_rate

    # Every scene at the same rate: no extra spread, the plain Wilson interval over all trials.
    r = clustered_rate([3, 3, 3, 3], [6, 6, 6, 6])
    assert r.design_effect == 1 and (r.low, r.high) == pytest.approx(wilson_ci(12, 24))
    # All-or-nothing scenes: variance of the ratio (k/(k-1)) sum (y - p m)^2 / n^2 = 4/3 * 100 / 400;
    # binomial p(1-p)/n = 1/80: design effect 20/3, Wilson on 20 / (20/3) = 3 trials.
    r = clustered_rate([5, 0, 5, 0], [5, 5, 5, 5])
    assert r.design_effect == pytest.approx(20 / 3)
    assert (r.low, r.high) == pytest.approx(wilson_ci(1.5, 3.0))
    assert clustered_rate([5, 5], [5, 5]).design_effect == 1  # p = 1: no binomial variance
    with pytest.raises(ValueError):
        clustered_rate([3], [2])


# ---- the run folder with a fake round ------------------------------------------------------------
def fake_round(pdoc, unit, todo=None):
    """A round with scripted stages whose outcomes come from the protocol's seeds (deterministic)."""
    p = clutter.protocol.clutter_protocol_from_json(pdoc)
    mode, scene, method = unit[0], int(unit[1]), unit[2]
    rng = np.random.default_rng(p.scene_seed(mode, scene) + (method == "topdown"))
    outcomes = rng.choice(["success", "success", "success", "not held", "no contact"], 4 * p.objects).tolist()
    rows = run(outcomes, p.objects)[0]
    for r in rows:
        r.update(mode=mode, scene=scene, method=method, scene_seed=p.scene_seed(mode, scene))
    return rows


def comparable(rows):
    return [{k: v for k, v in r.items() if not k.startswith("t_")} for r in rows]


@pytest.fixture
def object_list(tmp_path):
    path = tmp_path / "objects.txt"
    path.write_text("# test list\n" + "".join(f"random_urdfs/{i:03d}/{i:03d}.urdf\n" for i in range(8)))
    return str(path)


def protocol(object_list, **kw):
    kw = {"objects": 3, "scenes": 3, "modes": ["pile", "packed"], "methods": ["gmm", "topdown"], **kw}
    return clutter.ClutterProtocol(object_list=object_list, **kw)


def test_run_resume_and_jobs_give_the_same_rows(tmp_path, object_list):
    p = protocol(object_list)
    ref = clutter.run_clutter(p, tmp_path / "ref", progress=False, round_fn=fake_round)
    assert ref["rounds"] == ref["total"] == 12
    ref_rows = read_rows(tmp_path / "ref" / clutter.CLUTTER_CSV_NAME, clutter.CLUTTER_CSV)
    # Interrupted after 5 rounds, with half of a sixth round's rows written: resumed, the same rounds.
    part = clutter.run_clutter(p, tmp_path / "part", progress=False, report=False, max_rounds=5, round_fn=fake_round)
    assert part["rounds"] == 5
    torn = [r for r in fake_round(p.to_json(), p.rounds()[5]) if not r["stop"]]
    AttemptLog(tmp_path / "part" / clutter.CLUTTER_CSV_NAME, clutter.CLUTTER_CSV).append(torn)
    again = clutter.run_clutter(p, tmp_path / "part", progress=False, round_fn=fake_round)
    assert again["skipped"] == 5 and again["rounds"] == 12
    s_ref = json.loads((tmp_path / "ref" / "summary.json").read_text())
    s_part = json.loads((tmp_path / "part" / "summary.json").read_text())
    for mode in p.modes:
        for m in p.methods:
            for key in ("gsr", "dr", "outcomes", "stops", "per_scene"):
                assert s_part["results"][mode][m][key] == s_ref["results"][mode][m][key]
    two = clutter.run_clutter(p, tmp_path / "two", progress=False, jobs=2, round_fn=fake_round)
    rows2 = read_rows(tmp_path / "two" / clutter.CLUTTER_CSV_NAME, clutter.CLUTTER_CSV)
    key = lambda r: (r["mode"], r["scene"], r["method"], r["attempt"])  # noqa: E731
    assert comparable(sorted(rows2, key=key)) == comparable(sorted(ref_rows, key=key)) and two["ran"] == len(ref_rows)
    assert (tmp_path / "ref" / "report.md").read_text().count("| pile | gmm |") >= 1
    assert (tmp_path / "ref" / "clutter.png").stat().st_size > 1000


def test_seeds_are_shared_by_methods_and_differ_by_scene(object_list):
    p = protocol(object_list)
    assert p.scene_seed("pile", 0) == protocol(object_list, methods=["kde"]).scene_seed("pile", 0)
    assert len({p.scene_seed(m, s) for m in p.modes for s in range(3)}) == 6
    assert p.scene_seed("pile", 0) != protocol(object_list, seed=1).scene_seed("pile", 0)


def test_a_folder_of_another_protocol_is_refused(tmp_path, object_list):
    clutter.run_clutter(protocol(object_list), tmp_path / "r", progress=False, round_fn=fake_round)
    with pytest.raises(ValueError, match="different protocol"):
        clutter.run_clutter(protocol(object_list, scenes=4), tmp_path / "r", progress=False, round_fn=fake_round)


def test_bad_protocols(object_list, tmp_path):
    with pytest.raises(ValueError, match="unknown mode"):
        protocol(object_list, modes=["heap"])
    with pytest.raises(ValueError, match="unknown method"):
        protocol(object_list, methods=["vgn"])
    with pytest.raises(ValueError, match="objects"):
        protocol(object_list, objects=0)
    with pytest.raises(ValueError, match="lists 8 objects, a scene needs 9"):
        protocol(object_list, objects=9).check_inputs()


def test_cli_bad_input(tmp_path, capsys, object_list):
    from graspmix.cli.main import main

    for argv in (
        ["--mode", "heap"],
        ["--method", "gmm,vgn"],
        ["--objects", "0"],
        ["--object-list", str(tmp_path / "missing.txt")],
        ["--object-list", object_list, "--objects", "20"],
    ):
        capsys.readouterr()
        assert main(["clutter", "--out", str(tmp_path / "out"), *argv]) == 2
        err = capsys.readouterr().err.strip()
        assert err.startswith("graspmix_cli clutter: error:") and "\n" not in err
    assert not (tmp_path / "out" / clutter.CLUTTER_CSV_NAME).exists()


def test_the_split_files_are_disjoint():
    from graspmix.io import data_path, read_object_list

    lists = {n: read_object_list(data_path("objects", f"{n}.txt")) for n in ("test60", "clutter_dev", "clutter_test")}
    assert (len(lists["clutter_dev"]), len(lists["clutter_test"])) == (30, 60)
    for a in lists:
        assert len(set(lists[a])) == len(lists[a])
        for b in lists:
            assert a == b or not set(lists[a]) & set(lists[b])
    assert Path(clutter.default_object_list()).name == "clutter_test.txt"
