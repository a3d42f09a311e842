// synthesize_scene (include/graspmix/grasp/scene_synthesis.hpp): the whole path in one call and its result as
// arrays; called by bind_grasp after the synthesiser and the experts are bound.
#include <utility>

#include <pybind11/functional.h>

#include "common.hpp"
#include "grasp_convert.hpp"
#include "graspmix/grasp/scene_synthesis.hpp"
#include "settings.hpp"

namespace graspmix::py_bind {

namespace {

/// The input of one call: a depth image of `camera` at the pose, an organized cloud of `camera` at the pose, or
/// points with their viewpoints (the one given).
SceneInput to_input(const py::object& depth, const py::object& organized, const py::object& points,
                    const py::object& viewpoints, const std::optional<PinholeCamera>& camera, const py::object& pose) {
  const int given = !depth.is_none() + !organized.is_none() + !points.is_none();
  if (given != 1) throw py::value_error("synthesize_scene: give one of depth=, organized= or points=");
  if (points.is_none()) {
    if (!camera) throw py::value_error("synthesize_scene: a view needs its camera (a PinholeCamera)");
    if (!viewpoints.is_none())
      throw py::value_error("synthesize_scene: a view's viewpoint is its camera's pose; give no viewpoints");
    const Eigen::Isometry3d T = to_camera_pose(pose, "T_world_camera");
    if (!depth.is_none()) return DepthView{DepthImage(to_matrix(depth, "synthesize_scene: depth")), *camera, T};
    Vec3Array P(to_matrix(organized, "synthesize_scene: organized", 3));
    if (P.rows() != static_cast<Eigen::Index>(camera->height()) * camera->width())
      throw py::value_error("synthesize_scene: organized has " + std::to_string(P.rows()) + " rows, the camera " +
                            std::to_string(camera->width()) + " x " + std::to_string(camera->height()));
    return OrganizedView{std::move(P), *camera, T};  // a camera's image is megabytes: moved, not copied again
  }
  if (camera || !pose.is_none())
    throw py::value_error("synthesize_scene: points are in the world frame with their viewpoints; no camera or pose");
  return CloudInput{Vec3Array(to_matrix(points, "synthesize_scene: points", 3)),
                    to_points3(viewpoints, "synthesize_scene: viewpoints")};
}

/// settings_from<T>(obj), or unset for None: an optional part of the path turned off.
template <class T>
std::optional<T> optional_settings(const py::object& obj, const std::string& where) {
  if (obj.is_none()) return std::nullopt;
  return settings_from<T>(obj, py::dict(), where);
}

std::vector<SceneGraspType> to_types(const py::object& types) {
  std::vector<SceneGraspType> out;
  for (const py::handle& t : types) {
    const auto item = t.cast<py::tuple>();
    if (item.size() != 3)
      throw py::value_error("synthesize_scene: types are (synthesizer, name, log_reference or None) triples");
    SceneGraspType g;
    g.synthesizer = item[0].cast<std::shared_ptr<GraspSynthesizer>>();
    g.name = item[1].cast<std::string>();
    if (!item[2].is_none()) g.log_reference = to_number(item[2], "log_reference");
    out.push_back(std::move(g));
  }
  return out;
}

/// The ranked grasps' fields as arrays, one row a grasp: T_world_wrist (N, 7), joints and pregrasp (N, D),
/// log_likelihood (N), optimised (N), object and type (N); log_terms a list of N lists (each of its type's
/// term_names' length).
py::dict scene_columns(const SceneSynthesis& r) {
  const auto n = static_cast<Eigen::Index>(r.grasps.size());
  const Eigen::Index d = n ? r.grasps.front().grasp.joints.size() : 0;
  PoseArray wrists(n, 7);
  RowMatrixXd joints(n, d), pregrasp(n, d);
  Eigen::VectorXd ll(n);
  Eigen::VectorXi object(n), type(n);
  py::array_t<bool> optimised(n);
  auto opt = optimised.mutable_unchecked<1>();
  py::list terms;
  for (Eigen::Index i = 0; i < n; ++i) {
    const SceneGrasp& g = r.grasps[static_cast<std::size_t>(i)];
    wrists.row(i) = g.grasp.T_world_wrist.transpose();
    joints.row(i) = g.grasp.joints.transpose();
    pregrasp.row(i) = g.grasp.pregrasp.transpose();
    ll[i] = g.grasp.log_likelihood;
    opt(i) = g.grasp.optimised;
    object[i] = g.object;
    type[i] = g.type;
    const Eigen::VectorXd t = g.grasp.log_terms();
    terms.append(py::cast(std::vector<double>(t.data(), t.data() + t.size())));
  }
  py::dict out;
  out["T_world_wrist"] = wrists;
  out["joints"] = joints;
  out["pregrasp"] = pregrasp;
  out["log_likelihood"] = ll;
  out["optimised"] = optimised;
  out["object"] = object;
  out["type"] = type;
  out["log_terms"] = terms;
  return out;
}

py::dict timing_dict(const SceneSynthesisTiming& t) {
  py::dict d;
  d["segmentation"] = t.segmentation;
  d["occupancy"] = t.occupancy ? py::cast(*t.occupancy) : py::none();
  d["features"] = t.features;
  d["query"] = t.query;
  d["sampling"] = t.sampling;
  d["optimisation"] = t.optimisation;
  d["total"] = t.total;
  return d;
}

}  // namespace

void bind_scene_synthesis(py::module_& m) {
  m.attr("COMPLETED_VIEW_DISTANCE") = kCompletedViewDistance;
  m.attr("TYPE_REFERENCE_TERM") = kTypeReferenceTerm;

  py::class_<SceneSynthesis>(m, "SceneSynthesis", "What synthesize_scene made: the scene, the targets, ranked grasps.")
      .def_readonly("scene", &SceneSynthesis::scene, "the Segmentation (support plane and objects)")
      .def_readonly("viewpoints", &SceneSynthesis::viewpoints, "(M, 3) the camera of each scene point; (0, 3) unknown")
      .def_readonly("completion", &SceneSynthesis::completion, "the SceneCompletion of every object")
      .def_readonly("targets", &SceneSynthesis::targets, "the objects grasps were sampled on")
      .def_readonly("surfaces", &SceneSynthesis::surfaces, "per target, its SurfaceCloud")
      .def_readonly("term_names", &SceneSynthesis::term_names, "per grasp type, the names of a grasp's log_terms")
      .def_property_readonly(
          "timing", [](const SceneSynthesis& r) { return timing_dict(r.timing); },
          "seconds: segmentation (with the completion and the targets' choice), occupancy (None: no map), "
          "features, query, sampling, optimisation, total")
      .def_readonly("evaluations", &SceneSynthesis::evaluations)
      .def_readonly("rejected", &SceneSynthesis::rejected)
      .def("__len__", [](const SceneSynthesis& r) { return r.grasps.size(); })
      .def("columns", &scene_columns,
           "The ranked grasps as arrays: T_world_wrist (N, 7), joints, pregrasp (N, D), log_likelihood, optimised, "
           "object, type (N,), log_terms (a list of N lists, in the order of term_names[type])");

  m.def(
      "object_surface",
      [](const Segmentation& scene, const py::object& viewpoints,
         const std::vector<std::optional<Completion>>& completions, int index, const py::object& settings,
         const py::kwargs& kw) {
        const Vec3Array V =
            viewpoints.is_none() ? Vec3Array(0, 3) : Vec3Array(to_matrix(viewpoints, "object_surface: viewpoints", 3));
        const auto s = settings_from<SurfaceFeatureSettings>(settings, kw, "object_surface");
        py::gil_scoped_release release;
        return object_surface(scene, V, completions, index, s);
      },
      py::arg("scene"), py::arg("viewpoints"), py::arg("completions"), py::arg("index"), py::kw_only(),
      py::arg("settings") = py::none(),
      "Object `index`'s surface features as synthesize_scene computes them: a Segmentation, each of its points' "
      "camera (M, 3) or None, per object its Completion or None (include/graspmix/grasp/scene_synthesis.hpp).");
  m.def(
      "query_weights",
      [](const SurfaceCloud& surface, int n_observed, double completed_weight) -> py::object {
        const Eigen::VectorXd w = query_weights(surface, n_observed, completed_weight);
        return w.size() ? py::cast(w) : py::none();
      },
      py::arg("surface"), py::arg("n_observed"), py::arg("completed_weight"),
      "Each surface point's prior weight in the query densities (1 observed, completed_weight completed: the points "
      "from n_observed on); None when nothing is completed.");
  m.def(
      "synthesize_scene",
      [](const py::object& types, const py::object& depth, const py::object& organized, const py::object& points,
         const py::object& viewpoints, const std::optional<PinholeCamera>& camera, const py::object& pose,
         const py::object& plane, const std::string& target, const py::object& target_index,
         const py::object& target_point, const py::object& approach_axis, const py::object& reachable,
         const py::object& experts, const py::object& segmentation, const py::object& completion,
         const py::object& features, const py::object& synthesizer, const py::object& collision,
         const py::object& occupancy, const py::object& kinematic, const py::object& axis_alignment,
         const py::object& approach, const py::object& contact_quality, const py::object& grasp_depth) {
        const SceneInput input = to_input(depth, organized, points, viewpoints, camera, pose);
        SceneSynthesisSettings s;
        s.segmentation = settings_from<SegmentationSettings>(segmentation, py::dict(), "segmentation");
        s.completion = optional_settings<CompletionSettings>(completion, "completion");
        s.features = settings_from<SurfaceFeatureSettings>(features, py::dict(), "features");
        s.synthesizer = settings_from<SynthesizerSettings>(synthesizer, py::dict(), "synthesizer");
        s.collision = settings_from<CollisionSettings>(collision, py::dict(), "collision");
        s.occupancy = settings_from<OccupancySettings>(occupancy, py::dict(), "occupancy");
        s.kinematic = optional_settings<KinematicFeasibilitySettings>(kinematic, "kinematic");
        s.axis_alignment = settings_from<AxisAlignmentSettings>(axis_alignment, py::dict(), "axis_alignment");
        s.approach = optional_settings<ClearApproachSettings>(approach, "approach");
        s.contact_quality = optional_settings<ContactQualitySettings>(contact_quality, "contact_quality");
        s.grasp_depth = optional_settings<GraspDepthSettings>(grasp_depth, "grasp_depth");
        SceneRequest r;
        if (!plane.is_none()) r.plane = Eigen::Vector4d(to_vector(plane, "plane", 4));
        r.target = to_target(target, target_index, target_point, py::none());
        if (!approach_axis.is_none()) r.approach_axis = Eigen::Vector3d(to_vector(approach_axis, "approach_axis", 3));
        r.reachable = to_reachability(reachable);
        r.experts = to_experts(experts);
        const std::vector<SceneGraspType> t = to_types(types);
        py::gil_scoped_release release;  // a Python expert or reachability test takes the GIL back when called
        return synthesize_scene(input, t, s, r);
      },
      py::arg("types"), py::kw_only(), py::arg("depth") = py::none(), py::arg("organized") = py::none(),
      py::arg("points") = py::none(), py::arg("viewpoints") = py::none(), py::arg("camera") = py::none(),
      py::arg("T_world_camera") = py::none(), py::arg("plane") = py::none(), py::arg("target") = "all",
      py::arg("target_index") = py::none(), py::arg("target_point") = py::none(), py::arg("approach_axis") = py::none(),
      py::arg("reachable") = py::none(), py::arg("experts") = py::none(), py::arg("segmentation") = py::none(),
      py::arg("completion") = py::none(), py::arg("features") = py::none(), py::arg("synthesizer") = py::none(),
      py::arg("collision") = py::none(), py::arg("occupancy") = py::none(), py::arg("kinematic") = py::none(),
      py::arg("axis_alignment") = py::none(), py::arg("approach") = py::none(), py::arg("contact_quality") = py::none(),
      py::arg("grasp_depth") = py::none(),
      "The whole path from one view or a cloud to ranked grasps (include/graspmix/grasp/scene_synthesis.hpp).\n"
      "types: [(GraspSynthesizer, name, log_reference or None)]; the input: depth (H, W) metres with camera and\n"
      "T_world_camera [x, y, z, qx, qy, qz, qw], or organized (H * W, 3) sensor frame with camera and the pose, or\n"
      "points (N, 3) world frame with viewpoints (None, (3,) or (N, 3)); target: all | index | point | largest |\n"
      "nearest (target_index, target_point); the settings of each part (completion, kinematic, approach,\n"
      "contact_quality and grasp_depth None: that step off; the others None: their defaults).");
}

}  // namespace graspmix::py_bind
