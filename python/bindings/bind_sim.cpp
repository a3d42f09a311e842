// Grasp execution in Bullet: SimSettings, SimObject, SimResult, execute.
#include <memory>

#include "common.hpp"
#include "graspmix/core/se3.hpp"
#include "graspmix/sim/scene_sim.hpp"
#include "graspmix/sim/sim.hpp"
#include "settings.hpp"

namespace graspmix::py_bind {

namespace {

/// The objects of a scene (a sequence of SimObject) and their link poses (N, 7), checked.
std::vector<std::shared_ptr<SimObject>> scene_objects(const py::object& objects) {
  std::vector<std::shared_ptr<SimObject>> out;
  for (const py::handle& o : objects) {
    if (!py::isinstance<SimObject>(o)) throw py::value_error("objects: expected a sequence of SimObject");
    out.push_back(o.cast<std::shared_ptr<SimObject>>());
  }
  return out;
}

std::vector<Eigen::Isometry3d> scene_poses(const py::object& poses, size_t n) {
  const RowMatrixXd m = to_matrix(poses, "object_poses", 7, true);
  if (static_cast<size_t>(m.rows()) != n) {
    throw py::value_error("object_poses: " + std::to_string(m.rows()) + " poses for " + std::to_string(n) + " objects");
  }
  std::vector<Eigen::Isometry3d> out;
  for (Eigen::Index i = 0; i < m.rows(); ++i) out.push_back(pose_from_vector(m.row(i).transpose()));
  return out;
}

RowMatrixXd poses_matrix(const std::vector<Eigen::Isometry3d>& poses) {
  RowMatrixXd m(static_cast<Eigen::Index>(poses.size()), 7);
  for (size_t i = 0; i < poses.size(); ++i) m.row(static_cast<Eigen::Index>(i)) = pose_to_vector(poses[i]).transpose();
  return m;
}

std::vector<const SimObject*> raw(const std::vector<std::shared_ptr<SimObject>>& objects) {
  std::vector<const SimObject*> out;
  for (const auto& o : objects) out.push_back(o.get());
  return out;
}

void bind_scene_sim(py::module_& m) {
  py::class_<SceneSimResult>(m, "SceneSimResult", "The outcome of one grasp in a scene of several objects.")
      .def_readonly("result", &SceneSimResult::result,
                    "SimResult: outcome of the grasp; lift_height and object_pose of the object that rose most")
      .def_readonly("lifted", &SceneSimResult::lifted, "indices of the objects that rose and are held by the hand")
      .def_property_readonly(
          "object_poses", [](const SceneSimResult& r) { return poses_matrix(r.T_world_objects); },
          "(N, 7) every object's final link pose")
      .def_readonly("rise", &SceneSimResult::rise, "m each object's centre of mass rose")
      .def_readonly("moved", &SceneSimResult::moved, "m each object's link origin moved");

  py::class_<SettleResult>(m, "SettleResult", "A scene simulated without a hand until its objects rest.")
      .def_property_readonly(
          "object_poses", [](const SettleResult& r) { return poses_matrix(r.T_world_objects); },
          "(N, 7) every object's final link pose")
      .def_readonly("at_rest", &SettleResult::at_rest, "every object came to rest in time")
      .def_readonly("steps", &SettleResult::steps)
      .def_readonly("simulated_time", &SettleResult::simulated_time, "s");

  m.def(
      "sim_execute_scene",
      [](const std::shared_ptr<Hand>& hand, const py::object& objects, const py::object& object_poses,
         const py::object& T_world_wrist, const py::object& pregrasp, const py::object& grasp,
         const py::object& settings_obj, const py::kwargs& kw) {
        const SimSettings settings = settings_from<SimSettings>(settings_obj, kw, "sim_execute_scene");
        if (!hand) throw py::value_error("hand: expected a Hand, got None");
        const auto objs = scene_objects(objects);
        const std::vector<Eigen::Isometry3d> poses = scene_poses(object_poses, objs.size());
        const Eigen::Isometry3d Tw = pose_from_vector(to_vector(T_world_wrist, "T_world_wrist", 7));
        const Eigen::VectorXd qp = to_vector(pregrasp, "pregrasp_joints");
        const Eigen::VectorXd qg = to_vector(grasp, "grasp_joints");
        py::gil_scoped_release release;
        return execute_scene(*hand, raw(objs), poses, Tw, qp, qg, settings);
      },
      py::arg("hand"), py::arg("objects"), py::arg("object_poses"), py::arg("T_world_wrist"), py::arg("pregrasp"),
      py::arg("grasp"), py::arg("settings") = py::none(),
      "Executes one grasp among several objects (link poses (N, 7)); see graspmix.sim.scenes.execute_in_scene.");

  m.def(
      "sim_settle_scene",
      [](const py::object& objects, const py::object& object_poses, const py::object& settings_obj,
         const py::object& seconds_obj, const py::object& walls) {
        const double seconds = to_number(seconds_obj, "sim_settle_scene: seconds");
        const SimSettings settings = settings_from<SimSettings>(settings_obj, py::kwargs(), "sim_settle_scene");
        const auto objs = scene_objects(objects);
        const std::vector<Eigen::Isometry3d> poses = scene_poses(object_poses, objs.size());
        SettleWalls w;
        if (!walls.is_none()) {
          const Eigen::VectorXd v = to_vector(walls, "walls", 5);
          w.min = v.head<2>();
          w.max = v.segment<2>(2);
          w.height = v[4];
        }
        py::gil_scoped_release release;
        return settle_scene(raw(objs), poses, settings, seconds, walls.is_none() ? nullptr : &w);
      },
      py::arg("objects"), py::arg("object_poses"), py::arg("settings") = py::none(), py::arg("seconds") = 2.0,
      py::arg("walls") = py::none(),
      "Simulates the objects without a hand until they rest (at most `seconds`); walls: [xmin, ymin, xmax, ymax, "
      "height] of a box standing around them, or None.");
}

}  // namespace

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
      .field("close_speed", &SimSettings::close_speed, "m/s: fingertip speed limit while closing (sim_closing_speeds)")
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
          [](const SimObject& o, const py::object& x, const py::object& y, const py::object& q) {
            Eigen::Quaterniond quat = Eigen::Quaterniond::Identity();
            if (!q.is_none()) {
              const Eigen::VectorXd v = to_vector(q, "orientation", 4);
              quat = Eigen::Quaterniond(v[3], v[0], v[1], v[2]);
              if (!(quat.norm() > 0)) throw py::value_error("orientation: zero quaternion");
            }
            const double px = to_number(x, "rest_pose: x"), py_ = to_number(y, "rest_pose: y");
            return Eigen::Matrix<double, 7, 1>(pose_to_vector(o.rest_pose(px, py_, quat)));
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
  m.def(
      "sim_closing_speeds",
      [](const std::shared_ptr<Hand>& hand, const py::object& pregrasp, const py::object& grasp,
         const py::object& settings_obj, const py::kwargs& kw) {
        const SimSettings settings = settings_from<SimSettings>(settings_obj, kw, "sim_closing_speeds");
        if (!hand) throw py::value_error("hand: expected a Hand, got None");
        return closing_speeds(*hand, to_vector(pregrasp, "pregrasp_joints"), to_vector(grasp, "grasp_joints"),
                              settings);
      },
      py::arg("hand"), py::arg("pregrasp"), py::arg("grasp"), py::arg("settings") = py::none(),
      "The speed limit of every URDF joint (hand.joints order; m/s or rad/s, 0 for fixed joints) while the hand "
      "closes from pregrasp to grasp (arrays in hand.joint_names order): the fingertips move at close_speed m/s.");
  bind_scene_sim(m);
}

}  // namespace graspmix::py_bind
