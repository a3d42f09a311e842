#include "common.hpp"
#include "graspmix/core/se3.hpp"

namespace graspmix::py_bind {

void bind_core(py::module_& m) {
  m.def(
      "quat_log", [](const py::object& q) { return batch_quat_log(QuatArray(to_matrix(q, "quat_log: q", 4))); }, py::arg("q"),
      "eq:log_map on (N, 4) quaternions [x, y, z, w]: arccos(w) v/|v| after canonicalising w >= 0 -> (N, 3).");
  m.def(
      "quat_exp", [](const py::object& w) { return batch_quat_exp(Vec3Array(to_matrix(w, "quat_exp: w", 3))); }, py::arg("w"),
      "eq:exp_map on (N, 3) rotation vectors (half-angle convention) -> (N, 4) quaternions [x, y, z, w].");
  m.def(
      "pose_multiply",
      [](const py::object& a, const py::object& b) {
        return pose_multiply(PoseArray(to_matrix(a, "pose_multiply: a", 7)), PoseArray(to_matrix(b, "pose_multiply: b", 7)));
      },
      py::arg("a"), py::arg("b"),
      "Row-wise a o b over (N, 7) poses [x, y, z, qx, qy, qz, qw]; a side with one row is broadcast.");
  m.def(
      "pose_inverse", [](const py::object& a) { return pose_inverse(PoseArray(to_matrix(a, "pose_inverse: a", 7))); },
      py::arg("a"), "Row-wise inverse of (N, 7) poses.");
}

}  // namespace graspmix::py_bind
