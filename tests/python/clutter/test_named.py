"""The named-target evaluation's rules (graspmix.clutter.named) on constructed clouds: the target is a visible
object drawn by the seed alone, the named point lies on the target's top, and an execution's outcome names the
object that rose."""

import numpy as np
import pytest
from graspmix.clutter.named import NamedAttempt, choose_target, named_point, outcome_of, summarise
from graspmix.experiment.stats import wilson_ci


def cloud():
    """Object 0: 400 points of a 4 cm cube's top face at z = 0.04 and its sides; object 1: 30 points (hidden but
    for a sliver); object 2: 400 points; the table (-1): 1000 points at z = 0."""
    rng = np.random.default_rng(0)
    top = np.c_[rng.uniform(-0.02, 0.02, (200, 2)), np.full(200, 0.04)]
    side = np.c_[np.full(200, -0.02), rng.uniform(-0.02, 0.02, 200), rng.uniform(0.0, 0.04, 200)]
    obj2 = rng.uniform(0.1, 0.14, (400, 3))
    sliver = rng.uniform(-0.2, -0.19, (30, 3))
    table = np.c_[rng.uniform(-0.3, 0.3, (1000, 2)), np.zeros(1000)]
    points = np.vstack([top, side, sliver, obj2, table])
    labels = np.r_[np.zeros(400, int), np.ones(30, int), np.full(400, 2), np.full(1000, -1)]
    return points, labels


def test_the_target_is_a_visible_object_drawn_by_the_seed():
    points, labels = cloud()
    drawn = [choose_target(labels, 3, seed) for seed in range(40)]
    assert set(drawn) == {0, 2}  # object 1 has fewer points than an object the camera sees
    assert drawn == [choose_target(labels, 3, seed) for seed in range(40)]
    assert choose_target(np.full(10, -1), 3, 0) is None


def test_the_named_point_is_on_the_targets_top_near_its_middle():
    points, labels = cloud()
    p = named_point(points, labels, 0)
    assert p[2] >= 0.04 - 1e-12 and np.linalg.norm(p[:2]) < 0.01  # on the top face, near the face's centre
    assert np.min(np.linalg.norm(points[labels == 0] - p, axis=1)) == 0.0  # one of the target's own points
    with pytest.raises(ValueError, match="object 5 has no point"):
        named_point(points, labels, 5)


@pytest.mark.parametrize(
    "reason, lifted, outcome",
    [
        ("success", [1], "success"),
        ("success", [2], "wrong object"),
        ("two objects lifted", [1, 2], "two objects lifted"),
        ("two objects lifted", [0, 2], "wrong object"),
        ("start in collision", [], "start in collision"),
        ("no contact", [], "no contact"),
        ("not held", [], "not held"),
    ],
)
def test_an_outcome_names_what_rose(reason, lifted, outcome):
    assert outcome_of(reason, lifted, 1) == outcome


def test_the_summary_counts_and_bounds_the_rate():
    rows = [
        NamedAttempt("packed", i, i, 0, "u", [0, 0, 0], o, [])
        for i, o in enumerate(["success"] * 7 + ["wrong object"] * 2 + ["no contact"])
    ]
    s = summarise(rows)
    assert s["all"]["success"] == 7 and s["all"]["attempts"] == 10 and s["packed"]["outcomes"]["wrong object"] == 2
    assert s["all"]["ci95"] == pytest.approx(list(wilson_ci(7, 10)))
