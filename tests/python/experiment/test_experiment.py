"""The paper's experiment: statistics against scipy, seeds, the frame shared by acquisition and execution,
resuming, 1 vs 2 jobs vs Ray, the report from a CSV, the smoke preset end to end, and bad input."""

import dataclasses
import json
import math
import os
import signal
import subprocess
import sys
import textwrap
import time

import graspmix
import numpy as np
import pytest
from graspmix import cli, sim
from graspmix import experiment as ex
from graspmix.experiment.log import read_rows
from graspmix.experiment.report import build_report
from graspmix.experiment.stats import mean_ci, paired_ttest
from scipy import stats as sps

# ---- statistics --------------------------------------------------------------------------------


def test_mean_ci_matches_scipy_t_interval():
    x = np.array([0.55, 0.61, 0.48, 0.70, 0.58, 0.66, 0.52, 0.60, 0.63, 0.57])
    ci = mean_ci(x, 0.95)
    lo, hi = sps.t.interval(0.95, len(x) - 1, loc=x.mean(), scale=sps.sem(x))
    assert ci.mean == pytest.approx(x.mean(), abs=1e-15)
    assert (ci.low, ci.high) == pytest.approx((lo, hi), abs=1e-12)
    assert ci.std == pytest.approx(x.std(ddof=1))
    ci90 = mean_ci(x, 0.90)
    assert ci.low < ci90.low < ci90.high < ci.high
    one = mean_ci([0.4])
    assert one.mean == 0.4 and np.isnan(one.low) and np.isnan(one.high)


def test_paired_ttest_matches_scipy():
    rng = np.random.default_rng(3)
    kde = rng.integers(20, 40, 10) / 60
    gmm = np.clip(kde + rng.integers(0, 12, 10) / 60, 0, 1)
    tt = paired_ttest(gmm, kde)
    ref = sps.ttest_rel(gmm, kde)
    assert tt.t == pytest.approx(ref.statistic, rel=1e-12)
    assert tt.p == pytest.approx(ref.pvalue, rel=1e-12)
    assert tt.df == 9 and tt.n == 10
    d = gmm - kde
    lo, hi = sps.t.interval(0.95, 9, loc=d.mean(), scale=sps.sem(d))
    assert tt.mean_difference == pytest.approx(d.mean())
    assert (tt.ci_low, tt.ci_high) == pytest.approx((lo, hi), abs=1e-12)
    # The 95% interval excludes 0 exactly when the two-tailed p is below 0.05 (same t distribution).
    assert (tt.ci_low > 0 or tt.ci_high < 0) == (tt.p < 0.05)
    # Swapping the samples flips the sign of t and the difference, not p.
    sw = paired_ttest(kde, gmm)
    assert sw.t == pytest.approx(-tt.t) and sw.p == pytest.approx(tt.p)
    assert (sw.ci_low, sw.ci_high) == pytest.approx((-tt.ci_high, -tt.ci_low))


def test_paired_ttest_degenerate_and_bad_input():
    # A constant difference (up to the rounding of k/n rates): no spread, so t is infinite, not noise.
    a = np.array([50, 51, 49, 52]) / 60
    b = a - 10 / 60
    tt = paired_ttest(a, b)
    assert tt.t == np.inf and tt.p == 0.0 and tt.mean_difference == pytest.approx(1 / 6)
    same = paired_ttest(a, a)
    assert np.isnan(same.t) and np.isnan(same.p) and same.mean_difference == 0.0
    with pytest.raises(ValueError, match="same length"):
        paired_ttest([0.1, 0.2, 0.3], [0.1, 0.2])
    with pytest.raises(ValueError, match="at least 2"):
        paired_ttest([0.1], [0.2])
    with pytest.raises(ValueError, match="finite"):
        mean_ci([0.1, np.nan])
    with pytest.raises(ValueError, match="confidence"):
        mean_ci([0.1, 0.2], confidence=95)


# ---- seeds and the protocol --------------------------------------------------------------------


def test_seeds_are_stable_across_processes_and_distinct():
    # Python's hash() is salted per process; the derived seeds must not be.
    code = "from graspmix import experiment as ex; print(ex.derive_seed(0, 'synthesis', 'objects/mug.urdf', 3, 'B'))"
    outs = {
        subprocess.run(
            [sys.executable, "-c", code],
            env={**os.environ, "PYTHONHASHSEED": str(h)},
            capture_output=True,
            text=True,
            check=True,
        ).stdout.strip()
        for h in (1, 2)
    }
    assert outs == {str(ex.derive_seed(0, "synthesis", "objects/mug.urdf", 3, "B"))}
    p = ex.Protocol(objects=["objects/mug.urdf", "cube_small.urdf"], trials=3)
    acq = {p.acquisition_seed(o, t) for o in p.objects for t in range(3)}
    syn = {p.synthesis_seed(o, t, c) for o in p.objects for t in range(3) for c in "ABCD"}
    assert len(acq) == 6 and len(syn) == 24
    assert all(0 <= s < 2**31 for s in acq | syn)


def test_protocol_units_share_clouds():
    p = ex.Protocol(objects=["objects/mug.urdf"], trials=2)
    units = p.units()
    assert units == [
        ("objects/mug.urdf", 0, False),
        ("objects/mug.urdf", 0, True),
        ("objects/mug.urdf", 1, False),
        ("objects/mug.urdf", 1, True),
    ]
    # Noise-free conditions A and C share a unit (one cloud), both methods each.
    assert [(a[2], a[3]) for a in p.attempts(units[0])] == [("A", "gmm"), ("A", "kde"), ("C", "gmm"), ("C", "kde")]
    assert len(p.all_attempts()) == 2 * 4 * 2


def test_protocol_rejects_bad_values():
    with pytest.raises(ValueError, match="unknown condition 'E'"):
        ex.Protocol(objects=["cube_small.urdf"], conditions=["A", "E"])
    with pytest.raises(ValueError, match="unknown method 'svm'"):
        ex.Protocol(objects=["cube_small.urdf"], methods=["svm"])
    with pytest.raises(ValueError, match="trials"):
        ex.Protocol(objects=["cube_small.urdf"], trials=0)
    with pytest.raises(ValueError, match="twice"):
        ex.Protocol(objects=["cube_small.urdf", "cube_small.urdf"])
    with pytest.raises(ValueError, match="closing"):
        ex.Protocol(objects=["cube_small.urdf"], closing="half")
    with pytest.raises(ValueError, match="not found"):
        ex.Protocol(objects=["cube_small.urdf", "no/such/object.urdf"]).check_inputs()


# ---- the frame: acquisition, synthesis and execution agree ---------------------------------------


def test_grasp_synthesised_on_an_acquired_cloud_executes_in_the_same_frame():
    """The cloud lies on the object as the simulation places it, and a top grasp synthesised on the cloud
    lifts the object: acquisition, synthesis and execution share the world frame."""
    obj = "random_urdfs/057/057.urdf"
    acq = graspmix.sim.acquisition.acquire(obj, noise=False, seed=0, postprocess=ex.crop_above_plane(0.004))
    o = sim.load_object(obj)
    pose = sim.rest_pose(obj)
    v, _ = o.model.collision_mesh(o.model.link_names[0])
    from scipy.spatial.transform import Rotation

    w = Rotation.from_quat(pose[3:]).apply(v) + pose[:3]
    lo, hi = w.min(0), w.max(0)
    assert np.all(acq.points.min(0)[:2] >= lo[:2] - 0.003) and np.all(acq.points.max(0) <= hi + 0.003)
    assert np.all(acq.points.max(0)[:2] >= hi[:2] - 0.01) and np.all(acq.points.min(0)[:2] <= lo[:2] + 0.01)
    model = graspmix.GraspModel.load(graspmix.default_model_path("gmm"))
    opts = graspmix.SynthesisOptions().updated({"seed": 1, "segmentation.find_plane": False})
    g = model.synthesize(acq.points, opts, plane=[0, 0, 1, 0], viewpoints=acq.viewpoints, approach_axis=(0, 0, -1))
    best = g.best()
    assert Rotation.from_quat(best.T_world_wrist[3:]).apply([0, 0, 1])[2] < -0.9  # palm down: a top grasp
    # Executed as the experiment executes grasps (closing until the fingers stop on the object).
    r = sim.execute(obj, best, object_pose=pose, **ex.CLOSING["full"])
    assert r.success, r.reason
    # The same grasp moved 10 cm sideways touches nothing: the frame is not off by a shift the grasp survives.
    moved = dataclasses.replace(best, T_world_wrist=[best.T_world_wrist[0] + 0.1, *best.T_world_wrist[1:]])
    assert not sim.execute(obj, moved, object_pose=pose, **ex.CLOSING["full"]).success


# ---- runs: a small protocol --------------------------------------------------------------------


def small_protocol(**kw):
    """2 small objects x 2 trials x conditions B, C x both methods = 16 attempts in 8 units (seconds)."""
    fewer = graspmix.SynthesisOptions().updated({"sampling.n_samples": 60})
    base = dict(objects=graspmix.io.test_objects()[1:3], trials=2, conditions=["B", "C"], synthesis=fewer)
    base.update(kw)
    return ex.Protocol(**base)


def comparable(rows):
    """Rows without the wall times, sorted by key: what must not depend on jobs, executor or order."""
    cols = ex.KEY_COLUMNS + ex.RESULT_COLUMNS
    return sorted(tuple(r[c] for c in cols) for r in rows)


@pytest.fixture(scope="module")
def reference_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("ref") / "run"
    res = ex.run(small_protocol(), out, jobs=1, progress=False)
    assert res["ran"] == 16 and res["rows"] == 16
    return out


def test_small_run_rows(reference_run):
    rows = ex.read_rows(reference_run / ex.CSV_NAME)
    assert len(rows) == 16
    keys = {(r["object"], r["trial"], r["condition"], r["method"]) for r in rows}
    assert keys == set(small_protocol().all_attempts())
    for r in rows:
        assert r["reason"] in ("success", "not held", "no contact", "start in collision", "synthesis failed")
        assert r["success"] == (r["reason"] == "success")
        assert r["noise"] == (r["condition"] == "B") and r["optimise"] == (r["condition"] == "B")
        if r["reason"] != "synthesis failed":
            g = json.loads(r["grasp"])
            assert len(g["T_world_wrist"]) == 7
            assert r["t_query"] > 0 and r["t_sampling"] > 0 and r["t_execution"] > 0
            assert (r["t_optimisation"] > 1e-3) == bool(r["optimise"])  # without: the timer's microsecond
    # Both methods of one attempt saw the same cloud (same points count and acquisition seed), and
    # conditions sharing a noise setting share it too.
    by = {(r["object"], r["trial"], r["condition"], r["method"]): r for r in rows}
    for (o, t, c, m), r in by.items():
        other = by[(o, t, c, "kde" if m == "gmm" else "gmm")]
        assert (r["n_points"], r["acquisition_seed"], r["synthesis_seed"]) == (
            other["n_points"],
            other["acquisition_seed"],
            other["synthesis_seed"],
        )
    assert (reference_run / "summary.json").is_file() and (reference_run / "report.md").is_file()


def test_one_and_two_jobs_give_identical_rows(reference_run, tmp_path):
    ex.run(small_protocol(), tmp_path / "two", jobs=2, progress=False, report=False)
    assert comparable(ex.read_rows(tmp_path / "two" / ex.CSV_NAME)) == comparable(
        ex.read_rows(reference_run / ex.CSV_NAME)
    )


def test_ray_executor_gives_identical_rows(reference_run, tmp_path):
    pytest.importorskip("ray", reason="ray is not installed (pip install ray): the cluster executor is untested here")
    ex.run(small_protocol(), tmp_path / "ray", jobs=2, executor="ray", progress=False, report=False)
    assert comparable(ex.read_rows(tmp_path / "ray" / ex.CSV_NAME)) == comparable(
        ex.read_rows(reference_run / ex.CSV_NAME)
    )


def test_resume_after_a_stop_and_a_torn_line(reference_run, tmp_path):
    out = tmp_path / "run"
    first = ex.run(small_protocol(), out, jobs=1, progress=False, report=False, max_units=3)
    assert first["ran"] == 6
    csv_path = out / ex.CSV_NAME
    # A run killed while writing leaves a partial line: it must be dropped, not read as a row.
    full_line = csv_path.read_text().splitlines()[-1]
    with open(csv_path, "a") as f:
        f.write(full_line[: len(full_line) // 2])
    assert len(ex.read_rows(csv_path)) == 6
    second = ex.run(small_protocol(), out, jobs=2, progress=False, report=False)
    assert second["skipped"] == 6 and second["ran"] == 10
    rows = ex.read_rows(csv_path)
    assert len(rows) == 16 and csv_path.read_text().endswith("\n")
    assert comparable(rows) == comparable(ex.read_rows(reference_run / ex.CSV_NAME))
    # A third run has nothing left to do and adds nothing.
    third = ex.run(small_protocol(), out, jobs=1, progress=False, report=False)
    assert third["ran"] == 0 and len(ex.read_rows(csv_path)) == 16


def test_resume_after_the_process_is_killed(reference_run, tmp_path):
    """A real interruption: the run's process is killed (SIGKILL) as soon as its first rows are on disk."""
    out = tmp_path / "run"
    script = textwrap.dedent(f"""
        import graspmix
        from graspmix import experiment as ex
        if __name__ == "__main__":
            fewer = graspmix.SynthesisOptions().updated({{"sampling.n_samples": 60}})
            p = ex.Protocol(objects={small_protocol().objects!r}, trials=2, conditions=["B", "C"], synthesis=fewer)
            ex.run(p, {str(out)!r}, jobs=1, progress=False, report=False)
    """)
    proc = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    csv_path = out / ex.CSV_NAME
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and proc.poll() is None:
        if csv_path.is_file() and csv_path.read_text().count("\n") >= 2:  # header and at least one row
            break
        time.sleep(0.01)
    killed = proc.poll() is None
    if killed:
        proc.send_signal(signal.SIGKILL)
    proc.wait()
    before = len(ex.read_rows(csv_path))
    assert before >= 1
    if killed:
        assert before < 16
    res = ex.run(small_protocol(), out, jobs=1, progress=False, report=False)
    rows = ex.read_rows(csv_path)
    assert res["ran"] == 16 - before and len(rows) == 16
    assert comparable(rows) == comparable(ex.read_rows(reference_run / ex.CSV_NAME))


def test_ctrl_c_stops_a_parallel_run_promptly(tmp_path):
    """SIGINT (Ctrl-C) ends a 2-job run at once: workers are ended, the finished rows kept, exit status 130."""
    out = tmp_path / "run"
    proc = subprocess.Popen(
        [
            sys.executable,
            "-m",
            "graspmix.cli",
            "experiment",
            "--preset",
            "smoke",
            "--out",
            str(out),
            "--jobs",
            "2",
            "--quiet",
        ],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
        # A terminal's Ctrl-C reaches a process whose SIGINT is not ignored; a suite started in the background of a
        # non-interactive shell ignores it, the child would inherit that, and Python would then not raise
        # KeyboardInterrupt at all (the run finished with status 0).
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )
    csv_path = out / ex.CSV_NAME
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and proc.poll() is None:
        if csv_path.is_file() and csv_path.read_text().count("\n") >= 2:
            break
        time.sleep(0.01)
    if proc.poll() is not None:
        pytest.skip("the run finished before it could be interrupted")
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=60)
    assert proc.returncode == 130
    assert "the same command resumes" in err
    rows = ex.read_rows(csv_path)
    assert 1 <= len(rows) < 48 and len({(r["object"], r["trial"], r["condition"], r["method"]) for r in rows}) == len(
        rows
    )


def test_folder_of_another_protocol_is_refused_before_any_work(reference_run, tmp_path):
    import shutil

    out = tmp_path / "run"
    shutil.copytree(reference_run, out)
    before = (out / ex.CSV_NAME).read_bytes()
    with pytest.raises(ValueError, match="different protocol.*trials"):
        ex.run(small_protocol(trials=3), out, progress=False)
    assert (out / ex.CSV_NAME).read_bytes() == before
    other = tmp_path / "other"
    other.mkdir()
    (other / "notes.txt").write_text("mine")
    with pytest.raises(ValueError, match="not empty"):
        ex.run(small_protocol(), other, progress=False)


# ---- the report from a CSV ---------------------------------------------------------------------


def test_report_from_a_written_csv(tmp_path):
    """A CSV with known outcomes: the summary's rates, intervals and t-tests are those computed here with
    scipy, and the report files are written."""
    objects = graspmix.io.test_objects()[:5]
    p = ex.Protocol(objects=objects, trials=4, conditions=["A", "D"])
    out = ex.prepare_folder(p, tmp_path / "run")
    rng = np.random.default_rng(7)
    succ = {}
    rows = []
    for o, t, c, m in p.all_attempts():
        s = int(rng.random() < (0.8 if m == "gmm" else 0.5))
        succ[(o, t, c, m)] = s
        rows.append(
            {
                "object": o,
                "trial": t,
                "condition": c,
                "method": m,
                "noise": int(c == "D"),
                "optimise": int(c == "A"),
                "acquisition_seed": 1,
                "synthesis_seed": 2,
                "n_points": 100,
                "success": s,
                "reason": "success" if s else "not held",
                "lift_height": 0.2 * s,
                "contact_count": 2,
                "log_likelihood": -1.0,
                "grasp": "{}",
                "evaluations": 10,
                "rejected": 0,
                "error": "",
                "t_acquisition": 0.1,
                "t_features": 0.01,
                "t_query": 0.01 if m == "gmm" else 0.05,
                "t_sampling": 0.02 if m == "gmm" else 0.04,
                "t_optimisation": (0.03 if m == "gmm" else 0.09) if c == "A" else 0.0,
                "t_synthesis": 0.1,
                "t_execution": 0.02,
            }
        )
    ex.AttemptLog(out / ex.CSV_NAME).append(rows)
    assert cli.main(["report", str(out)]) == 0
    summary = json.loads((out / "summary.json").read_text())
    for c in ("A", "D"):
        rates = {m: [np.mean([succ[(o, t, c, m)] for o in objects]) for t in range(4)] for m in ("gmm", "kde")}
        for m in ("gmm", "kde"):
            e = summary["success_rate"][c][m]
            assert e["mean"] == pytest.approx(np.mean(rates[m]))
            assert [e["per_trial"][str(t)] for t in range(4)] == pytest.approx(rates[m])
            lo, hi = sps.t.interval(0.95, 3, loc=np.mean(rates[m]), scale=sps.sem(rates[m]))
            assert (e["ci_low"], e["ci_high"]) == pytest.approx((lo, hi))
        tt = summary["ttest_gmm_vs_kde"][c]
        ref = sps.ttest_rel(rates["gmm"], rates["kde"])
        assert tt["t"] == pytest.approx(ref.statistic) and tt["p"] == pytest.approx(ref.pvalue)
    rt = summary["runtime"]
    assert rt["conditions"] == ["A"]
    assert rt["median_s"]["gmm"]["total"] == pytest.approx(0.06)
    assert rt["median_s"]["kde"]["total"] == pytest.approx(0.18)
    assert rt["ratio_kde_over_gmm"]["total"] == pytest.approx(3.0)
    md = (out / "report.md").read_text()
    assert "![Success rate per condition and method](success_rates.png)" in md and "runtime.png" in md
    assert "| A: no depth noise, with optimisation |" in md
    # A row whose synthesis has some stage times but not all (a CSV edited by hand) is an error naming the row.
    csv_path = out / ex.CSV_NAME
    lines = csv_path.read_text().splitlines()
    header = lines[0].split(",")
    cells = lines[1].split(",")
    cells[header.index("t_sampling")] = ""
    csv_path.write_text("\n".join([lines[0], ",".join(cells), *lines[2:]]) + "\n")
    with pytest.raises(ValueError, match="row 1: t_sampling empty while t_query is given"):
        build_report(out)
    for f in ("success_rates.png", "runtime.png", "report.html"):
        assert (out / f).stat().st_size > 1000
    assert "data:image/png;base64," in (out / "report.html").read_text()


# ---- the command line --------------------------------------------------------------------------


def test_cli_smoke_preset_end_to_end(tmp_path, capsys):
    """The smoke preset (3 objects, 2 trials, A-D, GMM and KDE: 48 executions) with 2 jobs, then the
    report rebuilt from the CSV."""
    out = tmp_path / "smoke"
    assert cli.main(["experiment", "--preset", "smoke", "--out", str(out), "--jobs", "2", "--quiet"]) == 0
    text = capsys.readouterr().out
    assert "= 48 attempts" in text and "ran 48 attempts" in text
    rows = ex.read_rows(out / ex.CSV_NAME)
    assert len(rows) == 48
    doc = json.loads((out / "protocol.json").read_text())
    assert doc["protocol"]["trials"] == 2 and len(doc["protocol"]["objects"]) == 3
    assert doc["provenance"]["command"].startswith("graspmix_cli experiment --preset smoke")
    summary = json.loads((out / "summary.json").read_text())
    assert summary["attempts"] == {"done": 48, "expected": 48, "complete": True}
    assert set(summary["ttest_gmm_vs_kde"]) == {"A", "B", "C", "D"}
    first = (out / "summary.json").read_text()
    (out / "summary.json").unlink()
    (out / "report.md").unlink()
    assert cli.main(["report", str(out)]) == 0
    assert (out / "summary.json").read_text() == first and (out / "report.md").is_file()
    # Running it again resumes: nothing left to do.
    assert cli.main(["experiment", "--preset", "smoke", "--out", str(out), "--quiet"]) == 0
    assert "ran 0 attempts" in capsys.readouterr().out
    assert len(ex.read_rows(out / ex.CSV_NAME)) == 48


def cli_error(capsys, argv):
    assert cli.main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "error:" in err
    return err


def test_cli_bad_input_fails_before_any_work(tmp_path, capsys):
    out = tmp_path / "run"
    objs = tmp_path / "objects.txt"
    objs.write_text("# two objects\nobjects/mug.urdf\nrandom_urdfs/999/does_not_exist.urdf\n")
    assert "does_not_exist.urdf" in cli_error(capsys, ["experiment", "--out", str(out), "--objects", str(objs)])
    assert "no such objects file" in cli_error(
        capsys, ["experiment", "--out", str(out), "--objects", str(tmp_path / "none.txt")]
    )
    assert "unknown value 'E'" in cli_error(capsys, ["experiment", "--out", str(out), "--conditions", "A,E"])
    assert "unknown value 'svm'" in cli_error(capsys, ["experiment", "--out", str(out), "--methods", "gmm,svm"])
    assert "--jobs" in cli_error(capsys, ["experiment", "--out", str(out), "--jobs", "0"])
    assert not out.exists()
    assert "no protocol.json" in cli_error(capsys, ["report", str(tmp_path)])
    assert "no such run folder" in cli_error(capsys, ["report", str(tmp_path / "nothing")])
    # A folder of another protocol: refused, its files untouched.
    ok = tmp_path / "objs_ok.txt"
    ok.write_text("random_urdfs/057/057.urdf\n")
    p = ex.Protocol(objects=["random_urdfs/057/057.urdf"], trials=1)
    ex.prepare_folder(p, out)
    before = (out / "protocol.json").read_text()
    err = cli_error(capsys, ["experiment", "--out", str(out), "--objects", str(ok), "--trials", "2"])
    assert "different protocol" in err and "trials" in err
    assert (out / "protocol.json").read_text() == before and not (out / ex.CSV_NAME).exists()


def test_cli_benchmark(tmp_path, capsys):
    objs = tmp_path / "objects.txt"
    objs.write_text("random_urdfs/057/057.urdf\nrandom_urdfs/032/032.urdf\n")
    assert (
        cli.main(["benchmark", "--objects", str(objs), "--samples", "40", "--out", str(tmp_path / "b"), "--quiet"]) == 0
    )
    text = capsys.readouterr().out
    assert "KDE/GMM" in text and "query density estimation" in text
    res = json.loads((tmp_path / "b" / "benchmark.json").read_text())
    assert len(res["per_object_s"]["gmm"]["total"]) == 2
    for m in ("gmm", "kde"):
        assert res["median_s"][m]["total"] == pytest.approx(np.median(res["per_object_s"][m]["total"]))
    assert res["ratio_kde_over_gmm"]["total"] == pytest.approx(
        res["median_s"]["kde"]["total"] / res["median_s"]["gmm"]["total"]
    )
    assert (tmp_path / "b" / "benchmark.png").stat().st_size > 1000


def test_full_closing_holds_what_the_learnt_closing_misses():
    """A top grasp whose synthesised grasp joints (4 cm per finger, the demo box's width) are wider than a
    narrow object: the simulation's default target stops the fingers before they reach it; the protocol's
    "full" closing goes on until they stop on the object."""
    obj = "random_urdfs/675/675.urdf"  # 3 cm thin, 9 cm wide and tall
    o = sim.load_object(obj)
    pose = sim.rest_pose(obj)
    v, _ = o.model.collision_mesh(o.model.link_names[0])
    from scipy.spatial.transform import Rotation

    w = Rotation.from_quat(pose[3:]).apply(v) + pose[:3]
    lo, hi = w.min(0), w.max(0)
    half = (hi[:2] - lo[:2]).min() / 2
    yaw = 0.0 if hi[0] - lo[0] < hi[1] - lo[1] else math.pi / 2  # close across the narrow side
    g = sim.top_grasp((lo[:2] + hi[:2]) / 2, 0.055, 0.04, yaw=yaw, tip_height=max(0.01, hi[2] - 0.03))
    assert half < 0.04 - 0.5 * (0.055 - 0.04) - 0.005  # the default target stops short of the object
    assert not sim.execute(obj, g, object_pose=pose).success
    r = sim.execute(obj, g, object_pose=pose, **ex.CLOSING["full"])
    assert r.success, r.reason


def test_model_option_replaces_the_bundled_model_of_its_method(capsys):
    from graspmix.cli.experiment_commands import _protocol

    model = graspmix.data_path("models", "box_mug_side_wsg50_gmm.json")
    parse = cli.build_parser().parse_args
    p = _protocol(parse(["experiment", "--out", "x", "--model", str(model), "--methods", "gmm,kde"]))
    assert p.model_path("gmm") == model.resolve() and p.model_path("kde") == graspmix.default_model_path("kde")
    assert p.to_json()["models"]["gmm"]["file"] == model.name
    with pytest.raises(cli.common.CliError, match="is a gmm model, not one of --methods kde"):
        _protocol(parse(["experiment", "--out", "x", "--model", str(model), "--methods", "kde"]))


def test_the_log_names_the_executed_grasp_type_of_a_model_of_several(tmp_path):
    """A model of several grasp types logs which type was executed; the bundled one-type model's rows keep
    the old grasp entry (pose and joints only)."""
    objs = tmp_path / "objects.txt"
    objs.write_text("cube_small.urdf\n")
    rows = {}
    for name, model in (("two", graspmix.data_path("models", "box_mug_side_wsg50_gmm.json")), ("one", None)):
        argv = ["experiment", "--out", str(tmp_path / name), "--objects", str(objs), "--trials", "1"]
        argv += ["--conditions", "A", "--methods", "gmm", "--quiet"]
        assert cli.main(argv + (["--model", str(model)] if model else [])) == 0
        rows[name] = read_rows(tmp_path / name / ex.CSV_NAME)[0]
    two, one = (json.loads(rows[n]["grasp"]) for n in ("two", "one"))
    assert two["type"] in {"box_wsg50", "mug_side_wsg50"}
    assert list(one) == ["T_world_wrist", "pregrasp_joints", "grasp_joints"]
