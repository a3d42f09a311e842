"""The scene model over the C++ segmentation: the support plane and the objects of a depth camera's cloud,
target selection among the objects, the viewpoint inputs (a cloud given in a camera's frame), and one camera's
view as its driver gives it (a depth image with intrinsics or an organized cloud, segmented in image space).
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
from .views import (
    CameraView,
    depth_record,
    depth_view,
    organized_view,
    quaternion_order_note,
    read_depth,
    scene_input,
    segment_view,
    write_depth,
)

__all__ = [
    "CameraView",
    "scene_input",
    "quaternion_order_note",
    "depth_record",
    "depth_view",
    "organized_view",
    "read_depth",
    "write_depth",
    "segment_view",
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
