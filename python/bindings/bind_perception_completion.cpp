// Part of bind_perception: the completion of one object's unseen side (perception/completion.hpp).
#include "common.hpp"
#include "graspmix/perception/completion.hpp"
#include "settings.hpp"

namespace graspmix::py_bind {

namespace {

py::dict hypothesis_dict(const CompletionHypothesis& h, const py::object& kind) {
  py::dict d;
  d["kind"] = kind(static_cast<int>(h.kind));
  d["score"] = h.score;
  d["free_fraction"] = h.free_fraction;
  d["surface_fraction"] = h.surface_fraction;
  d["unseen_fraction"] = h.unseen_fraction;
  d["known_fraction"] = h.known_fraction;
  d["accepted"] = h.accepted;
  d["plane_or_axis"] = Eigen::Vector4d(h.plane_or_axis);
  return d;
}

}  // namespace

void bind_completion(py::module_& m) {
  const auto code = [](CompletionKind k) { return static_cast<int>(k); };
  const py::object kind = int_enum(
      m, "CompletionKind",
      {{"None_", code(CompletionKind::None)},
       {"Mirror", code(CompletionKind::Mirror)},
       {"Rotation", code(CompletionKind::Rotation)},
       {"Extrusion", code(CompletionKind::Extrusion)}},
      "Which hypothesis completed an object (complete_object): None_ (0, none accepted), Mirror (1, a vertical "
      "plane), Rotation (2, a vertical axis), Extrusion (3, walls down to the table).");
  SettingsClass<CompletionSettings>(m, "CompletionSettings", "The completion of an object's unseen side.")
      .field("spacing", &CompletionSettings::spacing,
             "m: the completed points' spacing, the profile's and footprint's bins")
      .field("max_free_fraction", &CompletionSettings::max_free_fraction,
             "a hypothesis with more of its points in seen-free space is refused, in [0, 1]")
      .field("min_unseen_fraction", &CompletionSettings::min_unseen_fraction,
             "a hypothesis with less of its points in unseen space is refused, in [0, 1]")
      .field("free_weight", &CompletionSettings::free_weight,
             "score = surface_fraction - free_weight * free_fraction (>= 0)")
      .field("mirror_angle_step", &CompletionSettings::mirror_angle_step,
             "rad: the step between mirror planes' orientations around each principal axis")
      .field("mirror_angle_steps", &CompletionSettings::mirror_angle_steps,
             "orientations each side of each principal axis (0..20)")
      .field("mirror_max_depth", &CompletionSettings::mirror_max_depth,
             "m: a mirror plane lies at most this far behind the footprint's far edge")
      .field("circle_max_rms", &CompletionSettings::circle_max_rms,
             "m: a rotation needs the outline's inliers within this RMS of their circle")
      .field("circle_min_inliers", &CompletionSettings::circle_min_inliers,
             "the fraction of the outline within 2 circle_max_rms of its circle for a rotation")
      .field("max_radius", &CompletionSettings::max_radius, "m: no rotation about a larger circle")
      .field("normal_radius", &CompletionSettings::normal_radius,
             "m: the neighbourhood of the observed points' normals (> spacing)")
      .field("max_scoring_points", &CompletionSettings::max_scoring_points,
             "points each hypothesis is scored on (>= 16)")
      .field("border_margin", &CompletionSettings::border_margin,
             "px: an observed point this close to a pinhole image's edge sets the border warning")
      .field("min_height", &CompletionSettings::min_height,
             "m: completed points lower than this above the support plane are dropped (the table's clearance)")
      .field("rotation_margin", &CompletionSettings::rotation_margin,
             "the rotation wins unless the best accepted mirror scores more than this above it")
      .field("observed_clearance", &CompletionSettings::observed_clearance,
             "m: no completed point within this of an observed point (the seen surface is not doubled)")
      .done();

  py::class_<Completion>(m, "Completion", "The completed unseen side of one object (complete_object).")
      .def_property_readonly(
          "kind", [kind](const Completion& c) { return kind(static_cast<int>(c.kind)); }, "the winner's CompletionKind")
      .def_readonly("score", &Completion::score, "the winner's score (0 for None_)")
      .def_readonly("points", &Completion::points, "(M, 3) the completed points only (m, world frame)")
      .def_readonly("normals", &Completion::normals, "(M, 3) unit normals, out of the object")
      .def_property_readonly(
          "hypotheses",
          [kind](const Completion& c) {
            py::list out;
            for (const auto& h : c.hypotheses) out.append(hypothesis_dict(h, kind));
            return out;
          },
          "Every hypothesis scored, the winner first when there is one: dicts of kind, score, free_fraction,\n"
          "surface_fraction, unseen_fraction, known_fraction, accepted, plane_or_axis (a mirror's plane [a, b, c, d];\n"
          "a rotation's axis foot on the table and radius [x, y, z, r]).")
      .def_readonly("warning", &Completion::warning, "why completion was limited, empty if nothing")
      .def_readonly("seconds", &Completion::seconds, "s, wall time")
      .def("__repr__", [kind](const Completion& c) {
        return "<Completion " + std::string(py::str(kind(static_cast<int>(c.kind)).attr("name"))) + " " +
               std::to_string(c.points.rows()) + " point(s)>";
      });

  m.def(
      "complete_object",
      [](const py::object& points, const py::object& plane, const VisibilityModel& visibility,
         const py::object& settings, const py::kwargs& kw) {
        const Vec3Array P(to_matrix(points, "complete_object: points", 3, true));
        const Eigen::Vector4d pl = to_vector(plane, "complete_object: plane", 4);
        const auto s = settings_from<CompletionSettings>(settings, kw, "complete_object");
        py::gil_scoped_release release;
        return complete_object(P, pl, visibility, s);
      },
      py::arg("points"), py::arg("plane"), py::arg("visibility"), py::kw_only(), py::arg("settings") = py::none(),
      ("The unseen side of one object: its observed points (N, 3; voxelised, world frame), the support plane\n"
       "[a, b, c, d] ((a, b, c) unit, towards the cameras) and the VisibilityModel of what the cameras saw\n"
       "(scene.result.visibility). Mirror, rotation and extrusion hypotheses are scored by the views (the rule:\n"
       "include/graspmix/perception/completion.hpp); ValueError naming the cause for bad input.\n" +
       settings_doc<CompletionSettings>())
          .c_str());

  py::class_<SceneCompletion>(m, "SceneCompletion", "Every object of a scene completed (complete_scene).")
      .def_readonly("completions", &SceneCompletion::completions, "per object, its Completion or None")
      .def_readonly("notes", &SceneCompletion::notes, "why objects were not completed, and the warnings")
      .def_readonly("seconds", &SceneCompletion::seconds, "s, wall time");
  m.def(
      "complete_scene",
      [](const Segmentation& scene, const py::object& settings, const py::kwargs& kw) {
        const auto s = settings_from<CompletionSettings>(settings, kw, "complete_scene");
        py::gil_scoped_release release;
        return complete_scene(scene, s);
      },
      py::arg("scene"), py::kw_only(), py::arg("settings") = py::none(),
      "Each object of a Segmentation completed (complete_object) from its visibility model and plane; without either "
      "nothing is completed and a note says why; an object complete_object refuses stays as seen, with a note. "
      "ValueError for settings out of range.");

  m.attr("POINT_TARGET_MAX_DISTANCE") = kPointTargetMaxDistance;
  m.def(
      "select_targets",
      [](const Segmentation& scene, const py::object& viewpoints, const std::string& kind, const py::object& index,
         const py::object& point, const py::object& camera) {
        const Vec3Array V =
            viewpoints.is_none() ? Vec3Array(0, 3) : Vec3Array(to_matrix(viewpoints, "select_targets: viewpoints", 3));
        return select_targets(scene, V, to_target(kind, index, point, camera));
      },
      py::arg("scene"), py::arg("viewpoints"), py::arg("kind"), py::kw_only(), py::arg("index") = py::none(),
      py::arg("point") = py::none(), py::arg("camera") = py::none(),
      "The object indices of a target (kind all, index, point, largest, nearest) in a Segmentation whose points were "
      "seen from viewpoints (M, 3) or None (include/graspmix/perception/targets.hpp).");
}

}  // namespace graspmix::py_bind
