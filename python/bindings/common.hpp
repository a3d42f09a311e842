#pragma once
// Conversions at the Python boundary: every array is checked for shape and named in the error, so a
// wrong shape is a ValueError that says which argument and what was expected, never a TypeError from
// overload resolution.
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "graspmix/core/types.hpp"
#include "graspmix/perception/targets.hpp"
#include "graspmix/robot/hand.hpp"

namespace graspmix::py_bind {

namespace py = pybind11;

/// A (N, cols) float64 matrix from any array-like; cols < 0 accepts any width. A 1-D input of
/// length cols is taken as one row when one_d_as_row is true.
RowMatrixXd to_matrix(const py::handle& obj, const char* name, int cols = -1, bool one_d_as_row = false);
/// A Python enum.IntEnum `name` of (member, value) pairs, with its docstring, set as m.<name> and returned (no
/// pybind11 enum type: numpy compares an IntEnum with the uint8 codes an array holds).
py::object int_enum(py::module_& m, const char* name, const std::vector<std::pair<const char*, int>>& members,
                    const char* doc);
/// Points (M, 3), a (3,) array as one row; None -> 0 rows.
Vec3Array to_points3(const py::object& obj, const char* name);
/// A 1-D float64 vector of length n (n < 0: any).
Eigen::VectorXd to_vector(const py::handle& obj, const char* name, Eigen::Index n = -1);
/// None -> 0; otherwise a non-negative integer.
std::uint64_t to_seed(const py::object& seed);
/// The most draws one sampling call makes: a bound checked before any memory is taken (10^7 poses are 560 MB).
inline constexpr long long kMaxDraws = 10'000'000;
/// A count (an int, not a bool) in [lo, hi]; ValueError naming `name` otherwise (never pybind11's TypeError
/// listing C++ signatures, never a cast that wraps or a std::bad_alloc).
int to_count(const py::handle& obj, const char* name, long long lo, long long hi);
/// A real number (an int or a float, not a bool), finite; ValueError naming `name` otherwise.
double to_number(const py::handle& obj, const char* name);
/// A C++ int: an integer (not a bool) in int's range; ValueError naming `name` otherwise (the callee checks
/// the range that makes sense).
inline int to_int(const py::handle& obj, const char* name) {
  return to_count(obj, name, std::numeric_limits<int>::min(), std::numeric_limits<int>::max());
}
/// Features for n rows: None means no features; a 1-D vector is repeated for every row.
RowMatrixXd to_features(const py::object& obj, Eigen::Index n_rows, int n_features, const char* name);
/// Optional weights: None -> empty.
Eigen::VectorXd to_weights(const py::object& obj, const char* name);

using HandPtr = std::shared_ptr<Hand>;

/// A batch of poses (N, 7), checked for shape.
inline PoseArray to_poses(const py::handle& obj, const char* name) { return PoseArray(to_matrix(obj, name, 7)); }
/// A filesystem path from str or os.PathLike.
std::string to_path(const py::object& obj, const char* name);
/// One configuration of `hand` from a name -> value mapping or an array in joint_names() order.
Eigen::VectorXd to_configuration(const Hand& hand, const py::handle& obj, const char* what);
/// N configurations: an (N, n_dofs) array, a sequence of mappings, or one configuration for all.
RowMatrixXd to_configurations(const Hand& hand, const py::handle& obj, const char* what);
/// A 7-vector pose.
Eigen::Isometry3d to_pose(const py::handle& obj, const char* name);
/// A camera's pose T_world_camera from [x, y, z, qx, qy, qz, qw] (graspmix::camera_pose's checks, naming `name`).
Eigen::Isometry3d to_camera_pose(const py::object& obj, const char* name);
/// A Target of kind "all", "index" (index), "point" (point (3,)), "largest" or "nearest" (camera (3,) or None).
Target to_target(const std::string& kind, const py::object& index, const py::object& point, const py::object& camera);

// One binder per layer, called in layer order by module.cpp.
void bind_core(py::module_& m);
void bind_density(py::module_& m);
void bind_perception(py::module_& m);
/// Part of bind_perception: cameras and the visibility model (bind_perception_visibility.cpp).
void bind_visibility(py::module_& m);
/// Part of bind_perception: completing an object's unseen side (bind_perception_completion.cpp).
void bind_completion(py::module_& m);
void bind_robot(py::module_& m);
void bind_grasp(py::module_& m);
/// Part of bind_grasp: the synthesiser (bind_grasp_synthesis.cpp).
void bind_synthesis(py::module_& m);
/// Part of bind_grasp: the whole path in one call, synthesize_scene (bind_grasp_scene.cpp).
void bind_scene_synthesis(py::module_& m);
/// Part of bind_grasp: the occupancy map and the solid volume (bind_grasp_occupancy.cpp).
void bind_occupancy(py::module_& m);
/// Part of bind_grasp: the contact-quality expert (bind_grasp_quality.cpp).
void bind_contact_quality(py::module_& m);
void bind_sim(py::module_& m);

}  // namespace graspmix::py_bind
