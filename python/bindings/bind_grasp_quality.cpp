// The contact-quality expert (grasp/contact_quality.hpp) and its settings and diagnostics, and the grasp-depth
// expert (grasp/grasp_depth.hpp); called by bind_grasp after the Expert base class is bound.
#include <algorithm>
#include <string>
#include <vector>

#include "common.hpp"
#include "graspmix/grasp/contact_quality.hpp"
#include "graspmix/grasp/grasp_depth.hpp"
#include "settings.hpp"

namespace graspmix::py_bind {

namespace {

/// An (N, F * k) block as an (N, F, k) array.
py::array_t<double> per_finger(const RowMatrixXd& m, Eigen::Index k) {
  const Eigen::Index n = m.rows(), f = k > 0 ? m.cols() / k : 0;
  py::array_t<double> out({static_cast<py::ssize_t>(n), static_cast<py::ssize_t>(f), static_cast<py::ssize_t>(k)});
  std::copy(m.data(), m.data() + m.size(), out.mutable_data());
  return out;
}

}  // namespace

void bind_contact_quality(py::module_& m) {
  SettingsClass<ContactQualitySettings>(m, "ContactQualitySettings",
                                        "The contact-quality expert (antipodal friction-cone deviation).")
      .field("friction", &ContactQualitySettings::friction,
             "Coulomb coefficient mu (> 0): the friction cone's half-angle is atan(mu)")
      .field("concentration", &ContactQualitySettings::concentration,
             "nats per radian beyond the friction cone, per contact")
      .field("air_penalty", &ContactQualitySettings::air_penalty, "nats per finger that closes on nothing")
      .field("patch_points", &ContactQualitySettings::patch_points,
             "a finger's contact patch of fewer cloud points than this is charged (0: off)")
      .field("patch_penalty", &ContactQualitySettings::patch_penalty,
             "nats: a patch of n < patch_points points costs patch_penalty * (1 - n / patch_points)")
      .field("contact_tolerance", &ContactQualitySettings::contact_tolerance,
             "m: points within this of a link's surface are in contact")
      .field("closing_steps", &ContactQualitySettings::closing_steps,
             "steps of the closing motion before bisection (links that do not translate)")
      .field("name", &ContactQualitySettings::name, "the key of its term in a grasp's experts table")
      .field("target_first", &ContactQualitySettings::target_first,
             "scene synthesis: a grasp whose finger, closing, meets another object's observed points before the\n"
             "target's is rejected (its target_first term -inf)")
      .done();

  py::class_<ContactQualityResult>(m, "ContactQualityResult",
                                   "The contacts of N grasps, F finger links each (expert.finger_links order).")
      .def_property_readonly(
          "links", [](const ContactQualityResult& r) { return r.links; },
          "(F,) the finger links (indices into Hand.link_names)")
      .def_readonly("t", &ContactQualityResult::t, "(N, F) closing parameter of each first contact (NaN: none)")
      .def_property_readonly(
          "joints",
          [](const ContactQualityResult& r) {
            const auto f = static_cast<Eigen::Index>(r.links.size());
            return per_finger(r.joints, f > 0 ? r.joints.cols() / f : 0);
          },
          "(N, F, D) the configuration at each finger's contact (NaN: none)")
      .def_property_readonly(
          "points", [](const ContactQualityResult& r) { return per_finger(r.points, 3); },
          "(N, F, 3) contact points, world frame (NaN: none)")
      .def_property_readonly(
          "normals", [](const ContactQualityResult& r) { return per_finger(r.normals, 3); },
          "(N, F, 3) contact normal axes, unit, pointing towards the finger (NaN: none)")
      .def_readonly("angles", &ContactQualityResult::angles,
                    "(N, F) angle (rad) between each contact's normal axis and the grasp line, in the scored pair")
      .def_readonly("patch_size", &ContactQualityResult::patch_size, "(N, F) points in each contact patch")
      .def_readonly("log_value", &ContactQualityResult::log_value, "(N,) log E");

  py::class_<ContactQualityExpert, Expert, std::shared_ptr<ContactQualityExpert>>(
      m, "ContactQualityExpert",
      "Soft: close the hand from each grasp's pre-grasp until each finger meets the cloud, then\n"
      "log E = -concentration * sum_i max(0, theta_i - atan(friction)) - air_penalty * (fingers on nothing)\n"
      "        - patch_penalty * sum_f max(0, 1 - patch_f / reference_f) (fingers that touch),\n"
      "theta_i the angle between contact i's normal axis and the line between the contacts, patch_f the points\n"
      "in finger f's contact patch, reference_f = min(patch_points, what finger f meets of a flat face:\n"
      "patch_reference)\n"
      "(include/graspmix/grasp/contact_quality.hpp).")
      .def(py::init([](HandPtr hand, const py::object& points, const py::object& normals, const ConfigModel& config,
                       const py::object& settings, const py::kwargs& kw) {
             if (!hand) throw py::value_error("hand: expected a Hand, got None");
             const ContactQualitySettings s =
                 settings_from<ContactQualitySettings>(settings, kw, "ContactQualityExpert");
             const Vec3Array P(to_matrix(points, "points", 3));
             const Vec3Array N(to_matrix(normals, "normals", 3));
             py::gil_scoped_release release;
             return std::make_shared<ContactQualityExpert>(std::move(hand), P, N, config, s);
           }),
           py::arg("hand"), py::arg("points"), py::arg("normals"), py::arg("pregrasp_config"), py::kw_only(),
           py::arg("settings") = py::none(),
           ("hand: Hand; points, normals: (N, 3) the object's cloud and surface normals (world frame; a normal's\n"
            "sign is ignored); pregrasp_config: a ConfigModel whose pregrasp_for(q) opens each grasp.\n" +
            settings_doc<ContactQualitySettings>())
               .c_str())
      .def(
          "evaluate",
          [](const ContactQualityExpert& e, const py::object& wrists, const py::object& joints) {
            const PoseArray w = to_poses(wrists, "wrists");
            const RowMatrixXd q = to_matrix(joints, "joints", e.hand().n_dofs());
            py::gil_scoped_release release;
            return e.evaluate(w, q);
          },
          py::arg("wrists"), py::arg("joints"),
          "The contacts, angles and log E of wrists (N, 7) and joints (N, D): a ContactQualityResult.")
      .def_property_readonly("finger_links", &ContactQualityExpert::finger_links,
                             "Indices (into Hand.link_names) of the links that close on the object.")
      .def_property_readonly(
          "finger_names",
          [](const ContactQualityExpert& e) {
            std::vector<std::string> out;
            for (const int l : e.finger_links()) out.push_back(e.hand().link_names()[static_cast<size_t>(l)]);
            return out;
          },
          "Names of the finger links.")
      .def_property_readonly("n_points", &ContactQualityExpert::n_points)
      .def_property_readonly("patch_reference", &ContactQualityExpert::patch_reference,
                             "Per finger, the patch size below which it is charged: min(patch_points, the patch it "
                             "makes closing face-on onto a flat wall of the cloud's spacing).")
      .def_property_readonly(
          "settings", [](const ContactQualityExpert& e) { return ContactQualitySettings(e.settings()); },
          "The ContactQualitySettings it was built with (a copy).");

  SettingsClass<GraspDepthSettings>(m, "GraspDepthSettings",
                                    "The grasp-depth expert (how far back the object reaches between the fingers).")
      .field("min_depth", &GraspDepthSettings::min_depth,
             "m: how far back from the fingertips' far end the object's points between the fingers must reach")
      .field("penalty", &GraspDepthSettings::penalty, "nats per metre short of min_depth")
      .field("min_radius", &GraspDepthSettings::min_radius,
             "m: the radius of the cylinder between the fingers is at least this")
      .field("name", &GraspDepthSettings::name, "the key of its term in a grasp's experts table")
      .done();

  py::class_<GraspDepthExpert, Expert, std::shared_ptr<GraspDepthExpert>>(
      m, "GraspDepthExpert",
      "Soft: log E = -penalty * max(0, min_depth - depth), depth how far back from the fingertips' far end (along\n"
      "the approach) the object's points inside the cylinder between the fingers reach\n"
      "(include/graspmix/grasp/grasp_depth.hpp).")
      .def(py::init([](HandPtr hand, const py::object& points, const py::object& settings, const py::kwargs& kw) {
             if (!hand) throw py::value_error("hand: expected a Hand, got None");
             const GraspDepthSettings s = settings_from<GraspDepthSettings>(settings, kw, "GraspDepthExpert");
             const Vec3Array P(to_matrix(points, "points", 3));
             py::gil_scoped_release release;
             return std::make_shared<GraspDepthExpert>(std::move(hand), P, s);
           }),
           py::arg("hand"), py::arg("points"), py::kw_only(), py::arg("settings") = py::none(),
           ("hand: Hand; points: (N, 3) the object's surface (world frame).\n" + settings_doc<GraspDepthSettings>())
               .c_str())
      .def(
          "depths",
          [](const GraspDepthExpert& e, const py::object& wrists, const py::object& joints) {
            const PoseArray w = to_poses(wrists, "wrists");
            const RowMatrixXd q = to_matrix(joints, "joints", e.hand().n_dofs());
            py::gil_scoped_release release;
            return Eigen::VectorXd(e.depths(w, q));
          },
          py::arg("wrists"), py::arg("joints"),
          "(N,) each grasp's depth (m) for wrists (N, 7) and joints (N, D), capped at min_depth.")
      .def_property_readonly(
          "settings", [](const GraspDepthExpert& e) { return GraspDepthSettings(e.settings()); },
          "The GraspDepthSettings it was built with (a copy).");
}

}  // namespace graspmix::py_bind
