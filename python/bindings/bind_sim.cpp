// Grasp execution in Bullet: SimSettings, SimObject, SimResult, execute.
#include <memory>

#include "common.hpp"
#include "graspmix/core/se3.hpp"
#include "graspmix/sim/sim.hpp"
#include "settings.hpp"

namespace graspmix::py_bind {

void bind_sim(py::module_& m) {
  SettingsClass<SimSettings>(m, "SimSettings", "Settings of a grasp execution in Bullet (units: m, s, N, kg).")
      .property(
          "gravity", [](const SimSettings& s) { return Eigen::Vector3d(s.gravity); },
          [](SimSettings& s, const py::object& g) { s.gravity = Eigen::Vector3d(to_vector(g, "gravity", 3)); },
          "m/s^2 (3,)")
      .field("time_step", &SimSettings::time_step, "s (pybullet's default)")
      .field("solver_iterations", &SimSettings::solver_iterations, "constraint solver iterations per step")
      .field("hand_friction", &SimSettings::hand_friction, "lateral friction coefficient of every hand link")
      .field("object_friction", &SimSettings::object_friction,
             "< 0: the URDF's <contact><lateral_friction> (0.5 if absent)")
      .field("support_friction", &SimSettings::support_friction, "lateral friction of the support plane")
      .field("object_mass", &SimSettings::object_mass, "kg; < 0: the URDF's")
      .field("grip_force", &SimSettings::grip_force, "N (N m): force limit of every finger joint motor")
      .field("close_speed", &SimSettings::close_speed, "m/s (rad/s): joint speed limit while closing")
      .field("close_overshoot", &SimSettings::close_overshoot,
             "motor targets lie this fraction of (grasp - pregrasp) past the grasp joints")
      .field("close_time", &SimSettings::close_time, "s spent closing before the lift")
      .field("position_gain", &SimSettings::position_gain, "1/s: joint velocity command = gain * position error")
      .field("lift_height", &SimSettings::lift_height, "m")
      .field("lift_speed", &SimSettings::lift_speed, "m/s")
      .field("lift_force", &SimSettings::lift_force, "N: force limit of the lift joint")
      .field("hold_time", &SimSettings::hold_time, "s held at the top")
      .field("start_penetration", &SimSettings::start_penetration,
             "m: a start penetrating deeper than this is 'start in collision'")
      .field("contact_distance", &SimSettings::contact_distance, "m: contact points closer than this count as touching")
      .field("success_fraction", &SimSettings::success_fraction, "the object must rise by this fraction of lift_height")
      .done();

  py::class_<SimObject, std::shared_ptr<SimObject>>(
      m, "SimObject", "An object to grasp from a one-link URDF: collision meshes as convex hulls, mass, friction.")
      .def_static(
          "from_urdf",
          [](const py::object& path) {
            const std::string p = to_path(path, "path");
            py::gil_scoped_release release;
            return std::make_shared<SimObject>(SimObject::from_urdf(p));
          },
          py::arg("path"), "Reads a one-link object URDF; ValueError names a missing or unusable file.")
      .def_property_readonly("source", &SimObject::source)
      .def_property_readonly("mass", &SimObject::mass, "kg")
      .def_property_readonly("lateral_friction", &SimObject::lateral_friction, "the URDF's <contact> value, -1 if none")
      .def_property_readonly("inertia_scaling", &SimObject::inertia_scaling,
                             "the URDF's <contact><inertia_scaling>, 1 if none")
      .def_property_readonly(
          "model", [](const SimObject& o) { return std::make_shared<Hand>(o.model()); },
          "The object as a (one-link) Hand: its collision geometry.")
      .def(
          "rest_pose",
          [](const SimObject& o, double x, double y, const py::object& q) {
            Eigen::Quaterniond quat = Eigen::Quaterniond::Identity();
            if (!q.is_none()) {
              const Eigen::VectorXd v = to_vector(q, "orientation", 4);
              quat = Eigen::Quaterniond(v[3], v[0], v[1], v[2]);
              if (!(quat.norm() > 0)) throw py::value_error("orientation: zero quaternion");
            }
            return Eigen::Matrix<double, 7, 1>(pose_to_vector(o.rest_pose(x, y, quat)));
          },
          py::arg("x") = 0.0, py::arg("y") = 0.0, py::arg("orientation") = py::none(),
          "The link pose (7,) resting the object on z = 0 at (x, y) with orientation [qx, qy, qz, qw].");

  py::class_<SimResult>(m, "SimResult", "The outcome of one grasp execution.")
      .def_readonly("success", &SimResult::success)
      .def_readonly("reason", &SimResult::reason, "'success', 'start in collision', 'no contact' or 'not held'")
      .def_readonly("lift_height", &SimResult::lift_height, "m the object's centre of mass rose")
      .def_readonly("contact_count", &SimResult::contact_count, "hand-object contact points at the end")
      .def_readonly("start_penetration", &SimResult::start_penetration, "m")
      .def_property_readonly(
          "object_pose",
          [](const SimResult& r) { return Eigen::Matrix<double, 7, 1>(pose_to_vector(r.T_world_object_final)); },
          "the object's final link pose (7,)")
      .def_readonly("steps", &SimResult::steps)
      .def_readonly("simulated_time", &SimResult::simulated_time, "s")
      .def_readonly("wall_time", &SimResult::wall_time, "s")
      .def("__repr__", [](const SimResult& r) {
        return "SimResult(success=" + std::string(r.success ? "True" : "False") + ", reason='" + r.reason +
               "', lift_height=" + std::to_string(r.lift_height) +
               ", contact_count=" + std::to_string(r.contact_count) + ")";
      });

  m.def(
      "sim_execute",
      [](const std::shared_ptr<Hand>& hand, const std::shared_ptr<SimObject>& object, const py::object& T_world_object,
         const py::object& T_world_wrist, const py::object& pregrasp, const py::object& grasp,
         const py::object& settings_obj, const py::kwargs& kw) {
        const SimSettings settings = settings_from<SimSettings>(settings_obj, kw, "sim_execute");
        if (!hand) throw py::value_error("hand: expected a Hand, got None");
        if (!object) throw py::value_error("object: expected a SimObject, got None");
        const Eigen::Isometry3d To = pose_from_vector(to_vector(T_world_object, "T_world_object", 7));
        const Eigen::Isometry3d Tw = pose_from_vector(to_vector(T_world_wrist, "T_world_wrist", 7));
        const Eigen::VectorXd qp = to_vector(pregrasp, "pregrasp_joints");
        const Eigen::VectorXd qg = to_vector(grasp, "grasp_joints");
        py::gil_scoped_release release;
        return execute(*hand, *object, To, Tw, qp, qg, settings);
      },
      py::arg("hand"), py::arg("object"), py::arg("T_world_object"), py::arg("T_world_wrist"), py::arg("pregrasp"),
      py::arg("grasp"), py::arg("settings") = py::none(),
      ("Executes one grasp in Bullet (arrays in hand.joint_names order); see graspmix.sim.execute.\n" +
       settings_doc<SimSettings>())
          .c_str());
}

}  // namespace graspmix::py_bind
