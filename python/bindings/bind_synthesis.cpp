// Contact models, the hand configuration model, constraint experts and the grasp synthesiser.
#include <pybind11/functional.h>

#include "common.hpp"
#include "graspmix/config_model.hpp"
#include "graspmix/contact_model.hpp"
#include "graspmix/experts.hpp"
#include "graspmix/synthesis.hpp"

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

void bind_synthesis(py::module_& m) {
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
