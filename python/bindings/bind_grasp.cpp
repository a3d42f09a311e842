// The grasp layer: the collision expert, contact models, the hand configuration model, constraint experts
// (the synthesiser is bound by bind_grasp_synthesis.cpp).
#include <pybind11/functional.h>

#include "common.hpp"
#include "grasp_convert.hpp"
#include "graspmix/grasp/approach.hpp"
#include "graspmix/grasp/collision.hpp"
#include "graspmix/grasp/config_model.hpp"
#include "graspmix/grasp/contact_model.hpp"
#include "graspmix/grasp/experts.hpp"
#include "graspmix/grasp/occupancy.hpp"
#include "graspmix/grasp/synthesis.hpp"
#include "settings.hpp"

namespace graspmix::py_bind {

namespace {

/// An optional axis setting for Python: None or (3,).
py::object optional_axis(const std::optional<Eigen::Vector3d>& a) {
  return a ? py::cast(Eigen::Vector3d(*a)) : py::object(py::none());
}
std::optional<Eigen::Vector3d> axis_or_none(const py::object& v, const char* name) {
  if (v.is_none()) return std::nullopt;
  return Eigen::Vector3d(to_vector(v, name, 3));
}

/// The collision expert W and its settings and results.
void bind_collision(py::module_& m) {
  bind_occupancy(m);
  SettingsClass<CollisionSettings>(m, "CollisionSettings", "The collision expert W(h) (eq:opt_criterion_std_col).")
      .property(
          "model", [](const CollisionSettings& s) { return to_string(s.model); },
          [](CollisionSettings& s, const py::object& v) {
            s.model = collision_model_from_string(setting_value<std::string>(v, "model"));
          },
          "surface (the cloud's points) | occupancy (an OccupancyMap of what the cameras saw)")
      .field("beta", &CollisionSettings::beta,
             "1/m: log W = -beta * total depth (2000: 0.5 mm of penetration costs one nat)")
      .field("point_radius", &CollisionSettings::point_radius, "m: cloud points are balls of this radius (>= 0)")
      .field("plane_margin", &CollisionSettings::plane_margin,
             "m: the support plane is raised by this much (negative: tolerate contact)")
      .field("cell_size", &CollisionSettings::cell_size, "m: grid cell of the cloud index; 0 picks one from the cloud")
      .field("orient_plane", &CollisionSettings::orient_plane,
             "flip the plane's sign so the cloud's mean lies on its free (positive) side")
      .field("contact_tolerance", &CollisionSettings::contact_tolerance,
             "m: depths up to this count as touching, not penetrating (a cloud is a noisy surface)")
      .field("inside_weight", &CollisionSettings::inside_weight,
             "m per point: each cloud point inside a link adds this much to the total depth (0: depths alone)")
      .field("reference_area", &CollisionSettings::reference_area,
             "m^2: the occupancy model charges a link's volume in blocked cells divided by this")
      .field(
          "volume", &CollisionSettings::volume,
          "keep the hand out of the objects' solid volume too (columns from the plane up to the points: solid_volume)")
      .field("volume_resolution", &CollisionSettings::volume_resolution, "m: the solid volume's cell, > 0")
      .field(
          "unseen_weight", &CollisionSettings::unseen_weight,
          "a link's volume in the unknown cells of a map of what the cameras saw (the occupancy model's, or the\n"
          "surface model's unseen map) outside the solid volume is charged at this weight (soft: in W, not in\n"
          "collision_free; an occupancy map with OccupancySettings.unknown_is_occupied charges them in full instead)")
      .field("unseen_margin", &CollisionSettings::unseen_margin,
             "m: with the volume, unseen space within this of it is not charged (>= 0)")
      .field(
          "occupied_cells", &CollisionSettings::occupied_cells,
          "the occupancy model charges the volume in occupied (seen surface) cells; False: their points' depths only")
      .done();

  py::class_<CollisionResult>(m, "CollisionResult",
                              "The collision expert for one configuration (depths in m, per link).")
      .def_readonly("cloud_depth", &CollisionResult::cloud_depth, "(n_links,) deepest cloud point inside each link.")
      .def_readonly("plane_depth", &CollisionResult::plane_depth,
                    "(n_links,) depth of each link below the support plane.")
      .def_readonly("points_inside", &CollisionResult::points_inside, "(n_links,) cloud points inside each link.")
      .def_readonly("unseen_depth", &CollisionResult::unseen_depth,
                    "(n_links,) the soft charge of unseen space (CollisionSettings.unseen_weight).")
      .def_readonly("total_depth", &CollisionResult::total_depth)
      .def_readonly("log_w", &CollisionResult::log_w, "log W(h) = -beta * total_depth.")
      .def_readonly("w", &CollisionResult::w, "W(h).")
      .def_readonly("collision_free", &CollisionResult::collision_free)
      .def("__repr__", [](const CollisionResult& r) {
        return "CollisionResult(total_depth=" + std::to_string(r.total_depth) + ", log_w=" + std::to_string(r.log_w) +
               ", collision_free=" + (r.collision_free ? "True" : "False") + ")";
      });

  py::class_<CollisionBatchResult>(m, "CollisionBatchResult", "The collision expert over N configurations.")
      .def_readonly("cloud_depth", &CollisionBatchResult::cloud_depth, "(N, n_links)")
      .def_readonly("plane_depth", &CollisionBatchResult::plane_depth, "(N, n_links)")
      .def_readonly("unseen_depth", &CollisionBatchResult::unseen_depth, "(N, n_links)")
      .def_readonly("total_depth", &CollisionBatchResult::total_depth, "(N,)")
      .def_readonly("log_w", &CollisionBatchResult::log_w, "(N,)")
      .def_readonly("w", &CollisionBatchResult::w, "(N,)")
      .def_readonly("collision_free", &CollisionBatchResult::collision_free, "(N,) bool");

  py::class_<CollisionExpert, std::shared_ptr<CollisionExpert>>(
      m, "CollisionExpert",
      "W(h) = exp(-beta * total penetration) of a hand through an object's cloud and below its support plane\n"
      "(eq:opt_criterion_std_col). Cloud depth of a link: the deepest cloud point inside it (exact for boxes,\n"
      "cylinders, spheres; meshes as their convex hulls); plane depth: the deepest point of the link below the\n"
      "plane (FCL half-space). The cloud is indexed once at construction.")
      .def(py::init([](HandPtr hand, const py::object& cloud, const py::object& plane,
                       const std::shared_ptr<OccupancyMap>& occupancy, const std::shared_ptr<OccupancyMap>& unseen,
                       const py::object& settings, const py::kwargs& kw) {
             if (!hand) throw py::value_error("hand: expected a Hand, got None");
             if (occupancy && unseen) {
               throw py::value_error(
                   "CollisionExpert: occupancy= or unseen=, not both (the occupancy model charges "
                   "the unknown cells of its own map)");
             }
             const CollisionSettings s = settings_from<CollisionSettings>(settings, kw, "CollisionExpert");
             std::optional<Eigen::Vector4d> pl;
             if (!plane.is_none()) pl = Eigen::Vector4d(to_vector(plane, "plane", 4));
             const Vec3Array P = cloud.is_none() ? Vec3Array(0, 3) : Vec3Array(to_matrix(cloud, "cloud", 3));
             py::gil_scoped_release release;
             if (occupancy) return std::make_shared<CollisionExpert>(std::move(hand), occupancy, P, pl, s);
             return std::make_shared<CollisionExpert>(std::move(hand), P, pl, s, unseen);
           }),
           py::arg("hand"), py::arg("cloud"), py::arg("plane") = py::none(), py::kw_only(),
           py::arg("occupancy") = py::none(), py::arg("unseen") = py::none(), py::arg("settings") = py::none(),
           ("hand: Hand; cloud: (N, 3) points (world frame) or None; plane: [a, b, c, d] of a x + b y + c z + d = 0\n"
            "or None; occupancy: an OccupancyMap for the occupancy model (its volume charge, plus the cloud's\n"
            "depths), None for the surface model (settings.model names it); unseen: the surface model's map whose\n"
            "unknown cells settings.unseen_weight charges (OccupancyMap.from_visibility), or None.\n" +
            settings_doc<CollisionSettings>())
               .c_str())
      .def(
          "evaluate",
          [](const CollisionExpert& e, const py::object& T_world_wrist, const py::object& joints) {
            const Eigen::Isometry3d W = to_pose(T_world_wrist, "T_world_wrist");
            const Eigen::VectorXd q = to_configuration(e.hand(), joints, "joints");
            return e.evaluate(W, q);
          },
          py::arg("T_world_wrist"), py::arg("joints"), "The expert for one wrist pose (7,) and configuration.")
      .def(
          "evaluate_batch",
          [](const CollisionExpert& e, const py::object& T_world_wrist, const py::object& joints) {
            const PoseArray W = to_matrix(T_world_wrist, "T_world_wrist", 7, true);
            const RowMatrixXd q = to_configurations(e.hand(), joints, "joints");
            py::gil_scoped_release release;
            return e.evaluate_batch(W, q);
          },
          py::arg("T_world_wrist"), py::arg("joints"),
          "The expert over wrists (N, 7) and joints (N, n_dofs) (or one for all).")
      .def(
          "log_w",
          [](const CollisionExpert& e, const py::object& T_world_wrist, const py::object& joints) {
            const PoseArray W = to_matrix(T_world_wrist, "T_world_wrist", 7, true);
            const RowMatrixXd q = to_configurations(e.hand(), joints, "joints");
            py::gil_scoped_release release;
            return Eigen::VectorXd(e.evaluate_batch(W, q).log_w);
          },
          py::arg("T_world_wrist"), py::arg("joints"), "log W(h) (N,) over wrists (N, 7) and joints.")
      .def(
          "collision_free",
          [](const CollisionExpert& e, const py::object& T_world_wrist, const py::object& joints) {
            const PoseArray W = to_matrix(T_world_wrist, "T_world_wrist", 7, true);
            const RowMatrixXd q = to_configurations(e.hand(), joints, "joints");
            py::gil_scoped_release release;
            return Eigen::Matrix<bool, Eigen::Dynamic, 1>(e.evaluate_batch(W, q).collision_free);
          },
          py::arg("T_world_wrist"), py::arg("joints"),
          "(N,) bool: no cloud point inside the hand and nothing below the plane.")
      .def_property_readonly(
          "plane",
          [](const CollisionExpert& e) -> py::object {
            if (!e.has_plane()) return py::none();
            return py::cast(Eigen::Vector4d(e.plane()));
          },
          "The normalised, oriented plane [a, b, c, d] (free side a x + b y + c z + d > 0), or None.")
      .def_property_readonly("n_points", &CollisionExpert::n_points)
      .def_property_readonly(
          "model", [](const CollisionExpert& e) { return to_string(e.settings().model); }, "surface | occupancy")
      .def_property_readonly(
          "occupancy",
          [](const CollisionExpert& e) -> py::object {
            return e.occupancy() ? py::cast(std::const_pointer_cast<OccupancyMap>(e.occupancy())) : py::none();
          },
          "The OccupancyMap of the occupancy model, or None.")
      .def_property_readonly(
          "volume",
          [](const CollisionExpert& e) -> py::object {
            return e.volume() ? py::cast(std::const_pointer_cast<OccupancyMap>(e.volume())) : py::none();
          },
          "The solid volume charged with settings.volume (an OccupancyMap: solid_volume), or None.")
      .def_property_readonly(
          "unseen",
          [](const CollisionExpert& e) -> py::object {
            return e.unseen() ? py::cast(std::const_pointer_cast<OccupancyMap>(e.unseen())) : py::none();
          },
          "The map whose unknown cells settings.unseen_weight charges (the occupancy model's, or unseen=), or None.")
      .def_property_readonly("cell_size", &CollisionExpert::cell_size, "The grid cell of the cloud index (m).")
      .def_property_readonly(
          "settings", [](const CollisionExpert& e) { return CollisionSettings(e.settings()); },
          "The CollisionSettings it was built with (a copy).")
      .def_property_readonly("beta", [](const CollisionExpert& e) { return e.settings().beta; })
      .def_property_readonly("point_radius", [](const CollisionExpert& e) { return e.settings().point_radius; })
      .def_property_readonly("plane_margin", [](const CollisionExpert& e) { return e.settings().plane_margin; });
}

/// Contact models M_i (and the demonstration's contact data) and the configuration model C.
void bind_models(py::module_& m) {
  SettingsClass<ContactSettings>(m, "ContactSettings", "How contact points are taken from a demonstration.")
      .field("max_distance", &ContactSettings::max_distance,
             "m: object points farther than this from a link's geometry are not its contacts")
      .field("lambda_", &ContactSettings::lambda, "1/m^2: a contact at distance d weighs exp(-lambda d^2)")
      .field("min_points", &ContactSettings::min_points, "a link with fewer contact points gets no contact model")
      .done();

  py::class_<ContactData>(m, "ContactData", "The demonstration data D_O of one link (contact_data).")
      .def_readonly("link", &ContactData::link)
      .def_readonly("indices", &ContactData::indices, "(M) object points used (rows of frames / features)")
      .def_readonly("u", &ContactData::u, "(M, 7) the link pose in each point's frame")
      .def_readonly("r", &ContactData::r, "(M, n) the points' features")
      .def_readonly("weights", &ContactData::weights, "(M) exp(-lambda d^2)")
      .def_readonly("distance", &ContactData::distance, "(M) m, from the point to the link's geometry (0 inside)")
      .def("__len__", [](const ContactData& d) { return d.u.rows(); });

  m.def(
      "contact_data",
      [](const HandPtr& hand, const py::object& link, const py::object& wrist, const py::object& joints,
         const py::object& frames, const py::object& features, const py::object& settings, const py::kwargs& kw) {
        const int link_index = to_int(link, "contact_data: link");
        const ContactSettings s = settings_from<ContactSettings>(settings, kw, "contact_data");
        return contact_data(*hand, link_index, to_pose(wrist, "T_world_wrist"),
                            to_configuration(*hand, joints, "joints"), to_poses(frames, "frames"),
                            to_matrix(features, "features"), s);
      },
      py::arg("hand"), py::arg("link"), py::arg("T_world_wrist"), py::arg("joints"), py::arg("frames"),
      py::arg("features"), py::arg("settings") = py::none(),
      ("eq:relative_pose_u_mixture: the contact points of one link in a demonstrated grasp, u = v^-1 o s.\n" +
       settings_doc<ContactSettings>())
          .c_str());

  py::class_<ContactModel>(m, "ContactModel", "M_i: one link's contact density.")
      .def(py::init([](const py::object& link, std::string name, std::shared_ptr<PoseDensity> density,
                       const py::object& n_points) {
             return ContactModel{to_int(link, "ContactModel: link"), std::move(name), std::move(density),
                                 to_count(n_points, "ContactModel: n_points", 0, std::numeric_limits<int>::max())};
           }),
           py::arg("link"), py::arg("link_name"), py::arg("density"), py::arg("n_points") = 0)
      .def_readonly("link", &ContactModel::link)
      .def_readonly("link_name", &ContactModel::link_name)
      .def_property_readonly("density",
                             [](const ContactModel& c) { return std::const_pointer_cast<PoseDensity>(c.density); })
      .def_readonly("n_points", &ContactModel::n_points);

  m.def(
      "learn_contact_models",
      [](const HandPtr& hand, const py::object& wrist, const py::object& joints, const py::object& frames,
         const py::object& features, const py::function& make_density, const py::object& settings,
         const py::kwargs& kw) {
        const ContactSettings s = settings_from<ContactSettings>(settings, kw, "learn_contact_models");
        auto factory = [&]() {
          py::object d = make_density();
          try {
            return d.cast<std::shared_ptr<PoseDensity>>();
          } catch (const py::cast_error&) {
            throw py::value_error("make_density must return a PoseMixture or PoseKDE");
          }
        };
        return learn_contact_models(*hand, to_pose(wrist, "T_world_wrist"), to_configuration(*hand, joints, "joints"),
                                    to_poses(frames, "frames"), to_matrix(features, "features"), factory, s);
      },
      py::arg("hand"), py::arg("T_world_wrist"), py::arg("joints"), py::arg("frames"), py::arg("features"),
      py::arg("make_density"), py::arg("settings") = py::none(),
      ("A contact model for every link with enough object points near it in the demonstrated grasp.\n" +
       settings_doc<ContactSettings>())
          .c_str());

  SettingsClass<ConfigModelSettings>(m, "ConfigModelSettings",
                                     "The hand configuration model C(h_c) (eq:manipulator_model).")
      .field("beta", &ConfigModelSettings::beta,
             "gamma range: configurations up to beta (h_e - h_g) either side of h_g")
      .field("n_kernels", &ConfigModelSettings::n_kernels, "kernels along the line (odd keeps one on h_g)")
      .field("alpha", &ConfigModelSettings::alpha, "decay of the kernel weights away from h_g (unitless)")
      .field("bandwidth", &ConfigModelSettings::bandwidth, "kernel std as a fraction of |h_e - h_g|")
      .field("min_bandwidth", &ConfigModelSettings::min_bandwidth, "floor of the kernel std (joint units: m or rad)")
      .done();

  py::class_<ConfigModel>(m, "ConfigModel", "C(h_c) of eq:manipulator_model.")
      .def(py::init([](const py::object& pregrasp, const py::object& grasp, const py::object& limits,
                       const py::object& settings, const py::kwargs& kw) {
             const ConfigModelSettings s = settings_from<ConfigModelSettings>(settings, kw, "ConfigModel");
             const Eigen::VectorXd g = to_vector(grasp, "grasp");
             return ConfigModel(to_vector(pregrasp, "pregrasp", g.size()), g, to_matrix(limits, "limits", 2), s);
           }),
           py::arg("pregrasp"), py::arg("grasp"), py::arg("limits"), py::arg("settings") = py::none(),
           ("pregrasp h_e and grasp h_g (D,), limits (D, 2).\n" + settings_doc<ConfigModelSettings>()).c_str())
      .def(
          "log_density",
          [](const ConfigModel& c, const py::object& q) { return c.log_density(to_matrix(q, "q", c.dim(), true)); },
          py::arg("q"))
      .def(
          "sample",
          [](const ConfigModel& c, const py::object& n, const py::object& seed) {
            const int count = to_count(n, "sample: n", 0, kMaxDraws);
            std::mt19937_64 rng(to_seed(seed));
            return c.sample(count, rng);
          },
          py::arg("n"), py::arg("seed") = py::none())
      .def("pregrasp_for",
           [](const ConfigModel& c, const py::object& q) { return c.pregrasp_for(to_vector(q, "q", c.dim())); })
      .def_property_readonly("pregrasp", &ConfigModel::pregrasp)
      .def_property_readonly("grasp", &ConfigModel::grasp)
      .def_property_readonly("limits", &ConfigModel::limits)
      .def_property_readonly("kernels", &ConfigModel::kernels)
      .def_property_readonly("sigma", &ConfigModel::sigma)
      .def_property_readonly("settings", [](const ConfigModel& c) { return ConfigModelSettings(c.settings()); });
}

/// The constraint experts E_k: the base class, the kinematic and approach experts, Python functions.
void bind_experts(py::module_& m) {
  py::class_<Expert, std::shared_ptr<Expert>>(m, "Expert", "A task-constraint expert E_k (log values per grasp).")
      .def_property_readonly("name", &Expert::name)
      .def(
          "log_value",
          [](const Expert& e, const py::object& wrists, const py::object& joints) {
            const PoseArray w = to_poses(wrists, "wrists");
            const RowMatrixXd q = to_matrix(joints, "joints");
            return e.log_value(GraspBatch{w, q});
          },
          py::arg("wrists"), py::arg("joints"));

  SettingsClass<KinematicFeasibilitySettings>(m, "KinematicFeasibilitySettings",
                                              "The hard kinematic-feasibility expert.")
      .field("plane_margin", &KinematicFeasibilitySettings::plane_margin,
             "m: links must stay this far above the support plane")
      .field("plane_tolerance", &KinematicFeasibilitySettings::plane_tolerance,
             "m: a link this little below the (raised) plane still counts as clear (rounding, not penetration)")
      .field("limit_tolerance", &KinematicFeasibilitySettings::limit_tolerance,
             "joint units (m or rad): slack allowed past the joint limits")
      .done();

  py::class_<KinematicFeasibilityExpert, Expert, std::shared_ptr<KinematicFeasibilityExpert>>(
      m, "KinematicFeasibilityExpert",
      "Hard: joint limits, no link below the support plane, and an optional reachability test "
      "reachable(wrists (N,7), joints (N,D)) -> bool array.")
      .def(py::init([](const HandPtr& hand, const py::object& plane, const py::object& reachable,
                       const py::object& settings, const py::kwargs& kw) {
             const KinematicFeasibilitySettings s =
                 settings_from<KinematicFeasibilitySettings>(settings, kw, "KinematicFeasibilityExpert");
             std::optional<Eigen::Vector4d> pl;
             if (!plane.is_none()) pl = Eigen::Vector4d(to_vector(plane, "plane", 4));
             return std::make_shared<KinematicFeasibilityExpert>(hand, pl, s, to_reachability(reachable));
           }),
           py::arg("hand"), py::arg("plane") = py::none(), py::arg("reachable") = py::none(), py::kw_only(),
           py::arg("settings") = py::none(), settings_doc<KinematicFeasibilitySettings>().c_str());

  SettingsClass<AxisAlignmentSettings>(m, "AxisAlignmentSettings", "The soft principal-axis alignment expert.")
      .property(
          "hand_axis", [](const AxisAlignmentSettings& s) { return optional_axis(s.hand_axis); },
          [](AxisAlignmentSettings& s, const py::object& v) { s.hand_axis = axis_or_none(v, "hand_axis"); },
          "(3,) the hand's axis in the wrist frame; None: the hand's approach_axis (Hand.approach_axis)")
      .field("concentration", &AxisAlignmentSettings::concentration,
             "nats: log E = concentration (cos theta - 1), so a 90-degree deviation costs this much")
      .field("name", &AxisAlignmentSettings::name, "the key of its term in a grasp's experts table")
      .done();

  py::class_<AxisAlignmentExpert, Expert, std::shared_ptr<AxisAlignmentExpert>>(
      m, "AxisAlignmentExpert", "Soft: log E = concentration (cos(angle between hand axis and world axis) - 1).")
      .def(py::init([](const py::object& axis, const py::object& hand_axis, const py::object& settings,
                       const std::shared_ptr<const Hand>& hand, py::kwargs kw) {
             if (!hand_axis.is_none()) kw["hand_axis"] = hand_axis;
             const AxisAlignmentSettings s = settings_from<AxisAlignmentSettings>(settings, kw, "AxisAlignmentExpert");
             return std::make_shared<AxisAlignmentExpert>(Eigen::Vector3d(to_vector(axis, "axis", 3)), s, hand.get());
           }),
           py::arg("axis"), py::arg("hand_axis") = py::none(), py::kw_only(), py::arg("settings") = py::none(),
           py::arg("hand") = py::none(),
           ("axis: (3,) the desired world axis; hand_axis=None: the settings' hand_axis, or (None too) the "
            "hand's approach_axis (without a hand: the wrist's +z).\n" +
            settings_doc<AxisAlignmentSettings>())
               .c_str());

  py::class_<CollisionFreeExpert, Expert, std::shared_ptr<CollisionFreeExpert>>(
      m, "CollisionFreeExpert",
      "Hard: the hand touches none of a CollisionExpert's cloud and plane at the grasp (and, given a "
      "ConfigModel, at its pre-grasp).")
      .def(py::init([](std::shared_ptr<CollisionExpert> collision, const std::optional<ConfigModel>& config,
                       std::string name) {
             if (!collision) throw py::value_error("CollisionFreeExpert: collision must be a CollisionExpert");
             return std::make_shared<CollisionFreeExpert>(std::move(collision), config, std::move(name));
           }),
           py::arg("collision"), py::arg("pregrasp_config") = py::none(), py::arg("name") = "collision_free",
           "collision: the CollisionExpert of what to keep clear of; pregrasp_config: a ConfigModel whose "
           "pregrasp_for(q) gives each grasp's pre-grasp, checked too (None: the grasp only).");

  SettingsClass<ClearApproachSettings>(m, "ClearApproachSettings", "The hard clear-approach expert.")
      .field("stand_off", &ClearApproachSettings::stand_off,
             "m: the hand starts this far back along its approach axis from the pre-grasp (>= 0)")
      .field("step", &ClearApproachSettings::step, "m: the path is checked at poses this far apart (> 0)")
      .field("clearance", &ClearApproachSettings::clearance,
             "m: the points of the collision expert the path is checked against are balls of this radius (scene "
             "synthesis builds it so), which the open hand may enter by that expert's contact tolerance (1 mm by "
             "default: the hand keeps 1 mm from every point)")
      .property(
          "hand_axis", [](const ClearApproachSettings& s) { return optional_axis(s.hand_axis); },
          [](ClearApproachSettings& s, const py::object& v) { s.hand_axis = axis_or_none(v, "hand_axis"); },
          "(3,) the approach axis in the wrist frame; None: the hand's approach_axis (Hand.approach_axis)")
      .field("name", &ClearApproachSettings::name, "the key of its term in a grasp's experts table")
      .done();

  py::class_<ClearApproachExpert, Expert, std::shared_ptr<ClearApproachExpert>>(
      m, "ClearApproachExpert",
      "Hard: the open hand (each grasp's pre-grasp) moves along its approach axis from the stand-off to the "
      "pre-grasp without touching the CollisionExpert's scene and plane.")
      .def(py::init([](std::shared_ptr<CollisionExpert> collision, const ConfigModel& config,
                       const py::object& settings, const py::kwargs& kw) {
             if (!collision) throw py::value_error("ClearApproachExpert: collision must be a CollisionExpert");
             const ClearApproachSettings s = settings_from<ClearApproachSettings>(settings, kw, "ClearApproachExpert");
             return std::make_shared<ClearApproachExpert>(std::move(collision), config, s);
           }),
           py::arg("collision"), py::arg("config"), py::kw_only(), py::arg("settings") = py::none(),
           ("collision: the CollisionExpert of the scene; config: the ConfigModel whose pregrasp_for(q) is the "
            "open hand.\n" +
            settings_doc<ClearApproachSettings>())
               .c_str())
      .def_property_readonly("offsets", &ClearApproachExpert::offsets,
                             "m: the distances back along the axis at which the open hand is checked");

  py::class_<FunctionExpert, Expert, std::shared_ptr<FunctionExpert>>(
      m, "FunctionExpert", "A user expert: fn(wrists (N,7), joints (N,D)) -> log E (N,), called once per batch.")
      .def(py::init([](std::string name, const py::function& fn) {
             FunctionExpert::Function f = [held = held_function(fn), name](const PoseArray& w, const RowMatrixXd& q) {
               py::gil_scoped_acquire gil;
               return to_vector((*held)(w, q), ("expert '" + name + "'").c_str());
             };
             return std::make_shared<FunctionExpert>(name, f);
           }),
           py::arg("name"), py::arg("fn"));
}

}  // namespace

void bind_grasp(py::module_& m) {
  bind_collision(m);
  bind_models(m);
  bind_experts(m);
  bind_contact_quality(m);
  bind_synthesis(m);
  bind_scene_synthesis(m);
}

}  // namespace graspmix::py_bind
