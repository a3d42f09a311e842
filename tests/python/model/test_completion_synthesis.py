"""Synthesis on the completed objects of a one-view scene (SynthesisOptions.completion): the completed points join
the target's surface with their prior weight and the points the hand keeps out of; the best grasp on a box seen
from one camera is checked against the box's true geometry (its size from the URDF, its pose from pybullet), not
against the completion itself. Without a viewpoint nothing is completed and the scene says so."""

from __future__ import annotations

import numpy as np
import pytest
from graspmix import CompletionKind, GraspModel, SynthesisOptions, default_model_path
from graspmix.model.scene_synthesis import object_surface, query_weights, segment_query
from graspmix.perception import segment_scene
from graspmix.sim.acquisition import AcquisitionSettings, Camera, acquire
from scipy.spatial.transform import Rotation

EYE = (0.0, -0.39, 0.44)  # 55 cm from the box's middle, 45 degrees above the table, in front of it (-y)
BOX = np.array([0.05, 0.07, 0.09])  # m: a box the WSG 50 (11 cm stroke) closes on across any side
FINGERS = ("finger_left", "finger_right")
PAD_HEIGHT = 0.0445  # m: the WSG 50's finger pads' centre above the finger frame (data/hands/wsg50.urdf)


@pytest.fixture(scope="module")
def seen_box(box_urdf):
    """One noisy view of a box turned 0.4 rad about z, and the bundled GMM model."""
    yaw = 0.4
    settings = AcquisitionSettings(
        cameras=[Camera(eye=EYE)], keep="scene", object_orientation=(0.0, 0.0, np.sin(yaw / 2), np.cos(yaw / 2))
    )
    acq = acquire(str(box_urdf(tuple(BOX))), noise=True, seed=3, settings=settings)
    return acq, GraspModel.load(default_model_path("gmm"))


def box_distance(acq, points):
    """Signed distance (m, negative inside) from points (N, 3) to the true box."""
    R = Rotation.from_quat(acq.object_pose[3:]).as_matrix()
    q = np.abs((points - acq.object_pose[:3]) @ R) - BOX / 2
    return np.linalg.norm(np.maximum(q, 0), axis=1) + np.minimum(q.max(axis=1), 0)


def test_completed_points_join_the_surface_with_their_weight_and_the_solid_points(seen_box):
    acq, model = seen_box
    opts = SynthesisOptions().updated({"query.completed_weight": 0.3})
    scene = segment_query((acq.points, acq.viewpoints), None, opts, model.features)
    assert len(scene.objects) == 1 and scene.completions[0].kind != CompletionKind.None_
    completed, normals = scene.completed(0)
    assert len(completed) > 100 and normals.shape == completed.shape
    assert len(scene.solid_points()) == len(scene.points) + len(completed)
    surface = object_surface(scene, 0, model.features)
    n_observed = scene.objects[0].n_points
    from_completion = np.asarray(surface.indices) >= n_observed
    assert from_completion.sum() > 0.8 * len(completed)  # a few edge points lack neighbours and are dropped
    # The completed points' normals point out of the true box (it is their own orientation that was given).
    R = Rotation.from_quat(acq.object_pose[3:]).as_matrix()
    out = (surface.points[from_completion] - acq.object_pose[:3]) @ R
    n_local = surface.normals[from_completion] @ R
    face = np.argmax(np.abs(out) - BOX / 2, axis=1)
    rows = np.arange(len(face))
    assert np.mean(n_local[rows, face] * np.sign(out[rows, face]) > 0.7) > 0.85
    w = query_weights(scene, 0, surface, opts)
    np.testing.assert_array_equal(w, np.where(from_completion, 0.3, 1.0))
    assert (
        query_weights(scene, 0, object_surface(scene, 0, model.features), opts.updated({"completion": None}))
        is not None
    )
    off = segment_query((acq.points, acq.viewpoints), None, opts.updated({"completion": None}), model.features)
    assert off.completions == [None] and query_weights(off, 0, object_surface(off, 0, model.features), opts) is None


VIEWS = [(0.4, 3), (0.0, 1), (0.8, 2), (1.2, 4), (0.2, 5)]  # (the box's turn about z (rad), the camera's noise seed)


def pads_on_the_box(model, acq, grasp) -> bool:
    """Both pads of a grasp within 1.5 cm of the true box's surface (the closing covers that travel) and neither
    more than 2 mm inside it."""
    links = model.hand.fk(np.asarray(grasp.T_world_wrist), grasp.grasp_joints)
    # Each finger's pad centre: on its inner face (the link's origin plane), PAD_HEIGHT along the approach.
    pads = np.array(
        [
            links[i][:3] + Rotation.from_quat(links[i][3:]).apply([0.0, 0.0, PAD_HEIGHT])
            for i in (model.hand.link_index(n) for n in FINGERS)
        ]
    )
    d = box_distance(acq, pads)
    return bool(np.all(d < 0.015) and np.all(d > -0.002))


def test_the_best_grasps_on_a_box_seen_from_one_side_hold_it_from_both_sides(box_urdf, seen_box):
    """Five views of the box (turned, noisy): of the best five grasps of each, those whose pads both end on the true
    box (the finger on the unseen side went where the box really is) are at least 20 of 25 with completion and
    more than without it (15 of 25 when this test was written). The completion's geometry alone: the solid volume,
    the soft charge of unseen space and contact quality's charge of small patches are off in both (with the last on,
    17 of 25 against 12: it prefers the box's faces seen whole, not where the completion put the back). The charge keeps the back finger out of the unseen side,
    often more than the 1.5 cm this test allows (10 of 25 with the defaults when they took it; the closing covers
    the travel), which is not what is tested here."""
    _, model = seen_box
    urdf = str(box_urdf(tuple(BOX)))
    counts = {"on": 0, "off": 0}
    for yaw, seed in VIEWS:
        settings = AcquisitionSettings(
            cameras=[Camera(eye=EYE)], keep="scene", object_orientation=(0.0, 0.0, np.sin(yaw / 2), np.cos(yaw / 2))
        )
        acq = acquire(urdf, noise=True, seed=seed, settings=settings)
        no_charge = SynthesisOptions().updated(
            {"collision.volume": False, "collision.unseen_weight": 0.0, "contact_quality.patch_points": 0.0}
        )
        for key, opts in (("on", no_charge), ("off", no_charge.updated({"completion": None}))):
            grasps = model.synthesize(acq.points, opts, viewpoints=acq.viewpoints)
            counts[key] += sum(pads_on_the_box(model, acq, g) for g in grasps.grasps[:5])
    assert counts["on"] >= 20 and counts["on"] > counts["off"], counts


def test_without_a_viewpoint_nothing_is_completed_and_the_scene_says_so(seen_box):
    acq, _ = seen_box
    scene = segment_scene(acq.points, plane=[0, 0, 1, 0]).complete()
    assert scene.completions == [None] * len(scene.objects)
    assert scene.notes == ["no viewpoint given: the unseen side of the objects is not completed"]
    assert len(scene.solid_points()) == len(scene.points)


def test_completion_options():
    opts = SynthesisOptions()
    assert opts.completion is not None and SynthesisOptions.paper().completion is None
    assert SynthesisOptions.from_dict(opts.to_dict()) == opts
    assert SynthesisOptions.from_dict(opts.updated({"completion": None}).to_dict()).completion is None
    assert opts.updated({"completion.spacing": 0.004}).completion.spacing == 0.004
    for bad in (0.0, 1.5):
        with pytest.raises(ValueError, match="completed_weight"):
            opts.updated({"query.completed_weight": bad})


def test_a_camera_in_the_support_plane_leaves_the_objects_as_seen_and_says_so(seen_box):
    """A camera in the given support plane: no object can be completed (complete_object refuses the view), the
    synthesis goes on with the observed points, and each object's note names it and the cause; bad completion
    settings stay an error."""
    acq, model = seen_box
    grasps = model.synthesize(acq.points, viewpoints=np.array([0.5, 0.1, 0.0]), plane=[0, 0, 1, 0])
    assert len(grasps) and grasps.scene.completions == [None]
    assert grasps.scene.notes and grasps.scene.notes[0].startswith("object 0 is not completed: ")
    assert "in or below the plane" in grasps.scene.notes[0]
    with pytest.raises(ValueError, match="spacing"):
        model.synthesize(acq.points, SynthesisOptions().updated({"completion.spacing": 5.0}), viewpoints=acq.viewpoints)
