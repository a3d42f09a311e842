// The grasp layer: the collision expert, contact models, the hand configuration model, constraint experts
// and the grasp synthesiser.
#include <pybind11/functional.h>

#include "common.hpp"
#include "graspmix/grasp/collision.hpp"
#include "graspmix/grasp/config_model.hpp"
#include "graspmix/grasp/contact_model.hpp"
#include "graspmix/grasp/experts.hpp"
#include "graspmix/grasp/synthesis.hpp"

namespace graspmix::py_bind {

namespace {

using ExpertList = std::vector<std::shared_ptr<const Expert>>;

ExpertList to_experts(const py::object& obj) {
  ExpertList out;
  if (obj.is_none()) return out;
  for (const py::handle& e : obj) {
    try {
      out.push_back(e.cast<std::shared_ptr<Expert>>());
    } catch (const py::cast_error&) {
      throw py::value_error("experts: every item must be a graspmix expert (got " +
                            std::string(py::str(py::type::of(e))) + ")");
    }
  }
  return out;
}

py::dict grasp_dict(const Grasp& g) {
  py::dict d;
  d["T_world_wrist"] = g.T_world_wrist;
  d["joints"] = g.joints;
  d["pregrasp"] = g.pregrasp;
  d["log_likelihood"] = g.log_likelihood;
  d["log_collision"] = g.log_collision;
  d["log_config"] = g.log_config;
  d["log_pregrasp"] = g.log_pregrasp;
  d["log_contact"] = g.log_contact;
  d["log_experts"] = g.log_experts;
  d["optimised"] = g.optimised;
  return d;
}

}  // namespace

void bind_grasp(py::module_& m) {
  py::class_<CollisionResult>(m, "CollisionResult", "The collision expert for one configuration (depths in m, per link).")
      .def_readonly("cloud_depth", &CollisionResult::cloud_depth, "(n_links,) deepest cloud point inside each link.")
      .def_readonly("plane_depth", &CollisionResult::plane_depth, "(n_links,) depth of each link below the support plane.")
      .def_readonly("points_inside", &CollisionResult::points_inside, "(n_links,) cloud points inside each link.")
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
      .def(py::init([](HandPtr hand, const py::object& cloud, const py::object& plane, double beta, double point_radius,
                       double plane_margin, double cell_size, bool orient_plane, double contact_tolerance,
                       double inside_weight) {
             if (!hand) throw py::value_error("hand: expected a Hand, got None");
             CollisionSettings s;
             s.beta = beta;
             s.point_radius = point_radius;
             s.plane_margin = plane_margin;
             s.cell_size = cell_size;
             s.orient_plane = orient_plane;
             s.contact_tolerance = contact_tolerance;
             s.inside_weight = inside_weight;
             const Vec3Array pts = cloud.is_none() ? Vec3Array(0, 3) : Vec3Array(to_matrix(cloud, "cloud", 3));
             std::optional<Eigen::Vector4d> pl;
             if (!plane.is_none()) pl = Eigen::Vector4d(to_vector(plane, "plane", 4));
             py::gil_scoped_release release;
             return std::make_shared<CollisionExpert>(hand, pts, pl, s);
           }),
           py::arg("hand"), py::arg("cloud"), py::arg("plane") = py::none(), py::arg("beta") = 1000.0,
           py::arg("point_radius") = 0.0, py::arg("plane_margin") = 0.0, py::arg("cell_size") = 0.0,
           py::arg("orient_plane") = true, py::arg("contact_tolerance") = 1e-9, py::arg("inside_weight") = 0.0,
           "hand: Hand; cloud: (N, 3) points (world frame); plane: [a, b, c, d] of a x + b y + c z + d = 0 or None;\n"
           "beta (1/m); point_radius (m, points as balls); plane_margin (m, the plane raised by it); cell_size (m,\n"
           "0 = automatic); orient_plane: flip the plane so the cloud lies on its positive side; contact_tolerance\n"
           "(m): depths up to it count as touching, not penetrating; inside_weight (m per point): each cloud point\n"
           "inside a link adds this to the total depth.")
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
          py::arg("T_world_wrist"), py::arg("joints"), "The expert over wrists (N, 7) and joints (N, n_dofs) (or one for all).")
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
          py::arg("T_world_wrist"), py::arg("joints"), "(N,) bool: no cloud point inside the hand and nothing below the plane.")
      .def_property_readonly("plane", [](const CollisionExpert& e) -> py::object {
        if (!e.has_plane()) return py::none();
        return py::cast(Eigen::Vector4d(e.plane()));
      }, "The normalised, oriented plane [a, b, c, d] (free side a x + b y + c z + d > 0), or None.")
      .def_property_readonly("n_points", &CollisionExpert::n_points)
      .def_property_readonly("cell_size", &CollisionExpert::cell_size, "The grid cell of the cloud index (m).")
      .def_property_readonly("beta", [](const CollisionExpert& e) { return e.settings().beta; })
      .def_property_readonly("point_radius", [](const CollisionExpert& e) { return e.settings().point_radius; })
      .def_property_readonly("plane_margin", [](const CollisionExpert& e) { return e.settings().plane_margin; });

  py::class_<ContactSettings>(m, "ContactSettings", "How contact points are taken from a demonstration.")
      .def(py::init<>())
      .def_readwrite("max_distance", &ContactSettings::max_distance, "m: farthest object point counted as a contact")
      .def_readwrite("lambda_", &ContactSettings::lambda, "1/m^2: contact weight exp(-lambda d^2)")
      .def_readwrite("min_points", &ContactSettings::min_points, "fewest contacts for a link to get a model");

  m.def(
      "contact_data",
      [](const HandPtr& hand, int link, const py::object& wrist, const py::object& joints, const py::object& frames,
         const py::object& features, const ContactSettings& s) {
        const ContactData d = contact_data(*hand, link, to_pose(wrist, "T_world_wrist"),
                                           to_configuration(*hand, joints, "joints"), to_poses(frames, "frames"),
                                           to_matrix(features, "features"), s);
        py::dict out;
        out["indices"] = d.indices;
        out["u"] = d.u;
        out["r"] = d.r;
        out["weights"] = d.weights;
        out["distance"] = d.distance;
        return out;
      },
      py::arg("hand"), py::arg("link"), py::arg("T_world_wrist"), py::arg("joints"), py::arg("frames"),
      py::arg("features"), py::arg("settings") = ContactSettings(),
      "eq:relative_pose_u_mixture: the contact points of one link in a demonstrated grasp, u = v^-1 o s.");

  py::class_<ContactModel>(m, "ContactModel", "M_i: one link's contact density.")
      .def(py::init([](int link, std::string name, std::shared_ptr<PoseDensity> density, int n_points) {
             return ContactModel{link, std::move(name), std::move(density), n_points};
           }),
           py::arg("link"), py::arg("link_name"), py::arg("density"), py::arg("n_points") = 0)
      .def_readonly("link", &ContactModel::link)
      .def_readonly("link_name", &ContactModel::link_name)
      .def_property_readonly("density", [](const ContactModel& c) { return std::const_pointer_cast<PoseDensity>(c.density); })
      .def_readonly("n_points", &ContactModel::n_points);

  m.def(
      "learn_contact_models",
      [](const HandPtr& hand, const py::object& wrist, const py::object& joints, const py::object& frames,
         const py::object& features, const py::function& make_density, const ContactSettings& s) {
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
      py::arg("make_density"), py::arg("settings") = ContactSettings(),
      "A contact model for every link with enough object points near it in the demonstrated grasp.");

  py::class_<ConfigModelSettings>(m, "ConfigModelSettings")
      .def(py::init<>())
      .def_readwrite("beta", &ConfigModelSettings::beta)
      .def_readwrite("n_kernels", &ConfigModelSettings::n_kernels)
      .def_readwrite("alpha", &ConfigModelSettings::alpha)
      .def_readwrite("bandwidth", &ConfigModelSettings::bandwidth)
      .def_readwrite("min_bandwidth", &ConfigModelSettings::min_bandwidth);

  py::class_<ConfigModel>(m, "ConfigModel", "C(h_c) of eq:manipulator_model.")
      .def(py::init([](const py::object& pregrasp, const py::object& grasp, const py::object& limits,
                       const ConfigModelSettings& s) {
             const Eigen::VectorXd g = to_vector(grasp, "grasp");
             return ConfigModel(to_vector(pregrasp, "pregrasp", g.size()), g, to_matrix(limits, "limits", 2), s);
           }),
           py::arg("pregrasp"), py::arg("grasp"), py::arg("limits"), py::arg("settings") = ConfigModelSettings())
      .def("log_density", [](const ConfigModel& c, const py::object& q) { return c.log_density(to_matrix(q, "q", c.dim(), true)); },
           py::arg("q"))
      .def(
          "sample",
          [](const ConfigModel& c, int n, const py::object& seed) {
            std::mt19937_64 rng(to_seed(seed));
            return c.sample(n, rng);
          },
          py::arg("n"), py::arg("seed") = py::none())
      .def("pregrasp_for", [](const ConfigModel& c, const py::object& q) { return c.pregrasp_for(to_vector(q, "q", c.dim())); })
      .def_property_readonly("pregrasp", &ConfigModel::pregrasp)
      .def_property_readonly("grasp", &ConfigModel::grasp)
      .def_property_readonly("limits", &ConfigModel::limits)
      .def_property_readonly("kernels", &ConfigModel::kernels)
      .def_property_readonly("sigma", &ConfigModel::sigma)
      .def_property_readonly("settings", &ConfigModel::settings);

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

  py::class_<KinematicFeasibilityExpert, Expert, std::shared_ptr<KinematicFeasibilityExpert>>(
      m, "KinematicFeasibilityExpert",
      "Hard: joint limits, no link below the support plane, and an optional reachability test "
      "reachable(wrists (N,7), joints (N,D)) -> bool array.")
      .def(py::init([](const HandPtr& hand, const py::object& plane, double margin, const py::object& reachable) {
             std::optional<Eigen::Vector4d> pl;
             if (!plane.is_none()) pl = Eigen::Vector4d(to_vector(plane, "plane", 4));
             KinematicFeasibilityExpert::Reachability fn;
             if (!reachable.is_none()) {
               py::function f = reachable;
               fn = [f](const PoseArray& w, const RowMatrixXd& q) {
                 py::gil_scoped_acquire gil;
                 const py::object r = f(w, q);
                 auto raw = py::array::ensure(r);
                 if (!raw || raw.ndim() != 1 || raw.dtype().kind() != 'b') {
                   throw py::value_error("reachable must return a 1-D array of booleans (one per grasp)");
                 }
                 auto a = py::array_t<bool, py::array::c_style | py::array::forcecast>::ensure(raw);
                 Eigen::Matrix<bool, Eigen::Dynamic, 1> out(a.shape(0));
                 for (py::ssize_t i = 0; i < a.shape(0); ++i) out[i] = a.at(i);
                 return out;
               };
             }
             return std::make_shared<KinematicFeasibilityExpert>(hand, pl, margin, fn);
           }),
           py::arg("hand"), py::arg("plane") = py::none(), py::arg("plane_margin") = 0.0, py::arg("reachable") = py::none());

  py::class_<AxisAlignmentExpert, Expert, std::shared_ptr<AxisAlignmentExpert>>(
      m, "AxisAlignmentExpert", "Soft: log E = concentration (cos(angle between hand axis and world axis) - 1).")
      .def(py::init([](const py::object& axis, const py::object& hand_axis, double concentration, std::string name) {
             return std::make_shared<AxisAlignmentExpert>(Eigen::Vector3d(to_vector(axis, "axis", 3)),
                                                          Eigen::Vector3d(to_vector(hand_axis, "hand_axis", 3)),
                                                          concentration, std::move(name));
           }),
           py::arg("axis"), py::arg("hand_axis") = Eigen::Vector3d::UnitZ(), py::arg("concentration") = 5.0,
           py::arg("name") = "approach_axis");

  py::class_<FunctionExpert, Expert, std::shared_ptr<FunctionExpert>>(
      m, "FunctionExpert", "A user expert: fn(wrists (N,7), joints (N,D)) -> log E (N,), called once per batch.")
      .def(py::init([](std::string name, const py::function& fn) {
             FunctionExpert::Function f = [fn, name](const PoseArray& w, const RowMatrixXd& q) {
               py::gil_scoped_acquire gil;
               return to_vector(fn(w, q), ("expert '" + name + "'").c_str());
             };
             return std::make_shared<FunctionExpert>(name, f);
           }),
           py::arg("name"), py::arg("fn"));

  py::class_<QuerySettings>(m, "QuerySettings")
      .def(py::init<>())
      .def_readwrite("n_samples", &QuerySettings::n_samples)
      .def_readwrite("n_components", &QuerySettings::n_components)
      .def_readwrite("max_iter", &QuerySettings::max_iter)
      .def_readwrite("reg_covar", &QuerySettings::reg_covar)
      .def_readwrite("frame_jitter", &QuerySettings::frame_jitter)
      .def_readwrite("jitter_sharpness", &QuerySettings::jitter_sharpness)
      .def_property(
          "kde_bandwidths",
          [](const QuerySettings& s) { return py::make_tuple(s.kde.position_bandwidth, s.kde.orientation_bandwidth); },
          [](QuerySettings& s, const py::tuple& t) {
            s.kde.position_bandwidth = t[0].cast<double>();
            s.kde.orientation_bandwidth = t[1].cast<double>();
          },
          "(position m, orientation rad) of KDE query kernels");

  py::class_<AnnealingSettings>(m, "AnnealingSettings")
      .def(py::init<>())
      .def_readwrite("iterations", &AnnealingSettings::iterations)
      .def_readwrite("initial_temperature", &AnnealingSettings::initial_temperature)
      .def_readwrite("position_step", &AnnealingSettings::position_step)
      .def_readwrite("rotation_step", &AnnealingSettings::rotation_step)
      .def_readwrite("joint_step", &AnnealingSettings::joint_step);

  py::class_<SynthesisSettings>(m, "SynthesisSettings")
      .def(py::init<>())
      .def_readwrite("n_samples", &SynthesisSettings::n_samples)
      .def_readwrite("n_optimise", &SynthesisSettings::n_optimise)
      .def_readwrite("optimise", &SynthesisSettings::optimise)
      .def_readwrite("clear_pregrasp", &SynthesisSettings::clear_pregrasp)
      .def_readwrite("max_sampling_rounds", &SynthesisSettings::max_sampling_rounds)
      .def_readwrite("query", &SynthesisSettings::query)
      .def_readwrite("annealing", &SynthesisSettings::annealing)
      .def_readwrite("seed", &SynthesisSettings::seed);

  py::class_<SynthesisResult>(m, "SynthesisResult")
      .def_property_readonly("grasps",
                             [](const SynthesisResult& r) {
                               py::list out;
                               for (const Grasp& g : r.grasps) out.append(grasp_dict(g));
                               return out;
                             })
      .def_readonly("contact_links", &SynthesisResult::contact_links)
      .def_readonly("expert_names", &SynthesisResult::expert_names)
      .def_readonly("evaluations", &SynthesisResult::evaluations)
      .def_readonly("rejected", &SynthesisResult::rejected)
      .def_property_readonly("timing", [](const SynthesisResult& r) {
        py::dict d;
        d["query"] = r.timing.query;
        d["sampling"] = r.timing.sampling;
        d["optimisation"] = r.timing.optimisation;
        d["total"] = r.timing.total;
        return d;
      });

  py::class_<QueryDensity>(m, "QueryDensity", "Q_i: one link's query density on an object.")
      .def_readonly("link", &QueryDensity::link)
      .def_readonly("link_name", &QueryDensity::link_name)
      .def_property_readonly("density", [](const QueryDensity& q) { return std::const_pointer_cast<PoseDensity>(q.density); });

  py::class_<GraspSynthesizer, std::shared_ptr<GraspSynthesizer>>(
      m, "GraspSynthesizer", "Query densities, sampling, ranking and annealing for one learnt model.")
      .def(py::init([](const HandPtr& hand, std::vector<ContactModel> models, ConfigModel config) {
             return std::make_shared<GraspSynthesizer>(hand, std::move(models), std::move(config));
           }),
           py::arg("hand"), py::arg("contact_models"), py::arg("config_model"))
      .def_property_readonly("method", &GraspSynthesizer::method)
      .def_property_readonly("contact_models", &GraspSynthesizer::contact_models)
      .def_property_readonly("config_model", &GraspSynthesizer::config_model)
      .def(
          "synthesize",
          [](const GraspSynthesizer& g, const py::object& frames, const py::object& features,
             const CollisionExpert& collision, const py::object& experts, const SynthesisSettings& s) {
            const PoseArray v = to_poses(frames, "frames");
            const RowMatrixXd r = to_matrix(features, "features");
            const ExpertList e = to_experts(experts);
            py::gil_scoped_release release;
            return g.synthesize(v, r, collision, e, s);
          },
          py::arg("frames"), py::arg("features"), py::arg("collision"), py::arg("experts") = py::none(),
          py::arg("settings") = SynthesisSettings())
      .def(
          "query_densities",
          [](const GraspSynthesizer& g, const py::object& frames, const py::object& features, const QuerySettings& s,
             const py::object& seed) {
            std::mt19937_64 rng(to_seed(seed));
            const PoseArray v = to_poses(frames, "frames");
            const RowMatrixXd r = to_matrix(features, "features");
            py::gil_scoped_release release;
            return g.query_densities(v, r, s, rng);
          },
          py::arg("frames"), py::arg("features"), py::arg("settings") = QuerySettings(), py::arg("seed") = py::none())
      .def(
          "sample_grasps",
          [](const GraspSynthesizer& g, const std::vector<QueryDensity>& q, int n, const py::object& seed) {
            std::mt19937_64 rng(to_seed(seed));
            PoseArray w;
            RowMatrixXd j;
            g.sample_grasps(q, n, rng, w, j);
            return py::make_tuple(w, j);
          },
          py::arg("query"), py::arg("n"), py::arg("seed") = py::none(), "(wrists (n, 7), joints (n, D)).")
      .def(
          "evaluate",
          [](const GraspSynthesizer& g, const std::vector<QueryDensity>& q, const CollisionExpert& collision,
             const py::object& experts, const py::object& wrists, const py::object& joints, bool clear_pregrasp) {
            const Evaluation e = g.evaluate(q, collision, to_experts(experts), to_poses(wrists, "wrists"),
                                            to_configurations(g.hand(), joints, "joints"), clear_pregrasp);
            py::dict d;
            d["total"] = e.total;
            d["log_collision"] = e.log_collision;
            d["log_config"] = e.log_config;
            d["log_pregrasp"] = e.log_pregrasp;
            d["log_contact"] = e.log_contact;
            d["log_experts"] = e.log_experts;
            return d;
          },
          py::arg("query"), py::arg("collision"), py::arg("experts"), py::arg("wrists"), py::arg("joints"),
          py::arg("clear_pregrasp") = true, "log L and its terms for a batch of grasps.");
}

}  // namespace graspmix::py_bind
