"""The scene model over the C++ segmentation: the support plane and the objects of a depth camera's cloud,
target selection among the objects, and the viewpoint inputs (a cloud given in a camera's frame).
Imports only io and the C++ core.

    scene = graspmix.segment_scene(points, viewpoints=camera_position)
    scene.objects[0].centroid, scene.select("nearest"), scene.to_dict()
"""

from .scene import (
    POINT_TARGET_MAX_DISTANCE,
    Scene,
    SceneObject,
    Target,
    camera_to_world,
    in_world,
    kind_name,
    parse_target,
    segment_scene,
)

__all__ = [
    "POINT_TARGET_MAX_DISTANCE",
    "Scene",
    "SceneObject",
    "Target",
    "camera_to_world",
    "in_world",
    "kind_name",
    "parse_target",
    "segment_scene",
]
