#include "common.hpp"
#include "graspmix/core/plane.hpp"
#include "graspmix/core/se3.hpp"

namespace graspmix::py_bind {

void bind_core(py::module_& m) {
  m.def(
      "quat_log", [](const py::object& q) { return batch_quat_log(QuatArray(to_matrix(q, "quat_log: q", 4))); },
      py::arg("q"),
      "eq:log_map on (N, 4) quaternions [x, y, z, w]: arccos(w) v/|v| after canonicalising w >= 0 -> (N, 3).");
  m.def(
      "quat_exp", [](const py::object& w) { return batch_quat_exp(Vec3Array(to_matrix(w, "quat_exp: w", 3))); },
      py::arg("w"),
      "eq:exp_map on (N, 3) rotation vectors (half-angle convention) -> (N, 4) quaternions [x, y, z, w].");
  m.def(
      "pose_multiply",
      [](const py::object& a, const py::object& b) {
        return pose_multiply(PoseArray(to_matrix(a, "pose_multiply: a", 7)),
                             PoseArray(to_matrix(b, "pose_multiply: b", 7)));
      },
      py::arg("a"), py::arg("b"),
      "Row-wise a o b over (N, 7) poses [x, y, z, qx, qy, qz, qw]; a side with one row is broadcast.");
  m.def(
      "pose_inverse", [](const py::object& a) { return pose_inverse(PoseArray(to_matrix(a, "pose_inverse: a", 7))); },
      py::arg("a"), "Row-wise inverse of (N, 7) poses.");
  m.def(
      "orient_plane",
      [](const py::object& plane, const py::object& points, const std::string& rule) {
        const Eigen::Vector4d p = to_vector(plane, "orient_plane: plane", 4);
        if (!p.allFinite() || p.head<3>().norm() == 0) {
          throw py::value_error("orient_plane: plane must be 4 finite numbers [a, b, c, d] with a non-zero normal");
        }
        const Vec3Array pts(to_matrix(points, "orient_plane: points", 3));
        PlaneSide side;
        if (rule == "majority")
          side = PlaneSide::Majority;
        else if (rule == "mean")
          side = PlaneSide::Mean;
        else if (rule == "median")
          side = PlaneSide::Median;
        else
          throw py::value_error("orient_plane: rule must be majority, mean or median, got '" + rule.substr(0, 80) +
                                "'");
        const Eigen::Vector4d out = orient_plane(p, pts, side);
        return out;
      },
      py::arg("plane"), py::arg("points"), py::arg("rule"),
      "The plane [a, b, c, d] or its negation, whichever has the points on its positive side by `rule`\n"
      "(majority: more points strictly above; mean / median of their signed heights >= 0). The one rule of\n"
      "docs/design.md that every part orienting a support plane uses.");
}

}  // namespace graspmix::py_bind
