// The grasp layer's synthesis: query densities, sampling, ranking, annealing (GraspSynthesizer) and their
// settings and results; called by bind_grasp after the experts it takes are bound.
#include <cmath>

#include <pybind11/functional.h>

#include "common.hpp"
#include "grasp_convert.hpp"
#include "graspmix/grasp/synthesis.hpp"
#include "settings.hpp"

namespace graspmix::py_bind {

namespace {

/// Rows of a per-grasp vector field stacked into an (N, k) array (k from the first grasp; all are equal).
template <typename Get>
RowMatrixXd stack_rows(const std::vector<Grasp>& grasps, Get get) {
  const Eigen::Index k = grasps.empty() ? 0 : get(grasps.front()).size();
  RowMatrixXd out(static_cast<Eigen::Index>(grasps.size()), k);
  for (std::size_t i = 0; i < grasps.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = get(grasps[i]).transpose();
  return out;
}

py::dict grasp_columns(const SynthesisResult& r) {
  const auto n = static_cast<Eigen::Index>(r.grasps.size());
  Eigen::VectorXd ll(n), wc(n), cc(n), wp(n);
  py::array_t<bool> optimised(n);
  auto opt = optimised.mutable_unchecked<1>();
  for (Eigen::Index i = 0; i < n; ++i) {
    const Grasp& g = r.grasps[static_cast<std::size_t>(i)];
    ll[i] = g.log_likelihood;
    wc[i] = g.log_collision;
    cc[i] = g.log_config;
    wp[i] = g.log_pregrasp;
    opt(i) = g.optimised;
  }
  py::dict d;
  d["T_world_wrist"] = stack_rows(r.grasps, [](const Grasp& g) -> Eigen::VectorXd { return g.T_world_wrist; });
  d["joints"] = stack_rows(r.grasps, [](const Grasp& g) -> const Eigen::VectorXd& { return g.joints; });
  d["pregrasp"] = stack_rows(r.grasps, [](const Grasp& g) -> const Eigen::VectorXd& { return g.pregrasp; });
  d["log_likelihood"] = ll;
  d["log_collision"] = wc;
  d["log_config"] = cc;
  d["log_pregrasp"] = wp;
  d["log_contact"] = stack_rows(r.grasps, [](const Grasp& g) -> const Eigen::VectorXd& { return g.log_contact; });
  d["log_experts"] = stack_rows(r.grasps, [](const Grasp& g) -> const Eigen::VectorXd& { return g.log_experts; });
  d["optimised"] = optimised;
  d["log_terms"] = stack_rows(r.grasps, [](const Grasp& g) -> Eigen::VectorXd { return g.log_terms(); });
  return d;
}

}  // namespace

void bind_synthesis(py::module_& m) {
  SettingsClass<QuerySettings>(m, "QuerySettings", "Contact query densities Q_i (eq:query_density_approx).")
      .field("n_samples", &QuerySettings::n_samples, "N_Q: samples per link to fit each query density from")
      .field("n_components", &QuerySettings::n_components, "K_Q: components of each query mixture (GMM models)")
      .field("max_iter", &QuerySettings::max_iter, "EM iterations of the query mixtures")
      .field("reg_covar", &QuerySettings::reg_covar, "added to the query mixtures' covariance diagonals")
      .field("kde", &QuerySettings::kde, "KdeSettings of KDE query densities (features unused)")
      .field("frame_jitter", &QuerySettings::frame_jitter,
             "rotate each sampled surface frame about its normal by up to pi exp(-jitter_sharpness ((k1 - k2) / k1)^2)")
      .field("jitter_sharpness", &QuerySettings::jitter_sharpness, "s of Kopicki's rule above")
      .field("completed_weight", &QuerySettings::completed_weight,
             "prior weight of a completed (unseen) point in the query densities, an observed one's being 1")
      .property(
          "link_floor",
          [](const QuerySettings& s) { return s.link_floor ? py::cast(*s.link_floor) : py::object(py::none()); },
          [](QuerySettings& s, const py::object& v) {
            if (v.is_none()) {
              s.link_floor.reset();
              return;
            }
            if (is_kind_of<double>(v)) {
              try {
                const double f = v.cast<double>();
                if (std::isfinite(f)) {
                  s.link_floor = f;
                  return;
                }
              } catch (const py::cast_error&) {
              }
            }
            throw py::value_error("setting 'link_floor': " + std::string(py::repr(v)).substr(0, 80) +
                                  " is not valid: expected a finite number or None");
          },
          "nats or None: each link's contact term is log(Q_i + exp(link_floor)); None: log Q_i (the paper's)")
      .done();

  SettingsClass<AnnealingSettings>(m, "AnnealingSettings", "Simulated annealing of the best candidates.")
      .field("iterations", &AnnealingSettings::iterations, "the paper's 100")
      .field("initial_temperature", &AnnealingSettings::initial_temperature, "the paper's 1.0, falling linearly to 0")
      .field("position_step", &AnnealingSettings::position_step,
             "m: std of wrist translation proposals at temperature 1")
      .field("rotation_step", &AnnealingSettings::rotation_step,
             "rad: std of wrist rotation proposals at temperature 1")
      .field("joint_step", &AnnealingSettings::joint_step,
             "std of joint proposals at temperature 1, in units of the config model's kernel std")
      .done();

  SettingsClass<SamplingSettings>(m, "SamplingSettings", "How many grasps are drawn, kept and annealed.")
      .field("n_samples", &SamplingSettings::n_samples, "grasps sampled, ranked and returned")
      .field("n_optimise", &SamplingSettings::n_optimise, "the best this many are optimised")
      .field("optimise", &SamplingSettings::optimise, "anneal the best n_optimise")
      .field("clear_pregrasp", &SamplingSettings::clear_pregrasp,
             "an extra collision expert on the pre-grasp configuration (log W of the opened hand)")
      .field("max_sampling_rounds", &SamplingSettings::max_sampling_rounds,
             "batches of n_samples drawn at most until n_samples grasps pass every hard expert")
      .field("topdown_seeds", &SamplingSettings::topdown_seeds,
             "scene synthesis adds each object's top-down seeds (grasp/topdown_seeds.hpp) to the drawn grasps")
      .field("oversample", &SamplingSettings::oversample,
             "oversample * n_samples grasps are drawn and ranked, the best n_samples returned (1: the paper's)")
      .done();
  m.attr("MAX_OVERSAMPLE") = kMaxOversample;

  SettingsClass<SynthesizerSettings>(m, "SynthesizerSettings",
                                     "What GraspSynthesizer.synthesize needs besides the object and the experts (scene "
                                     "synthesis builds it from graspmix.SynthesisOptions).")
      .field("sampling", &SynthesizerSettings::sampling, "SamplingSettings")
      .field("query", &SynthesizerSettings::query, "QuerySettings")
      .field("annealing", &SynthesizerSettings::annealing, "AnnealingSettings")
      .seed("seed", &SynthesizerSettings::seed, "seeds everything random in synthesis (None: 0)")
      .done();

  py::class_<Grasp>(m, "Grasp", "One synthesised grasp and its log-likelihood terms.")
      .def_readonly("T_world_wrist", &Grasp::T_world_wrist, "(7,) [x, y, z, qx, qy, qz, qw]")
      .def_readonly("joints", &Grasp::joints, "grasp configuration h_c (Hand.joint_names order)")
      .def_readonly("pregrasp", &Grasp::pregrasp, "the configuration to approach with")
      .def_readonly("log_likelihood", &Grasp::log_likelihood, "log L (eq:opt_criterion_extended)")
      .def_readonly("log_collision", &Grasp::log_collision, "log W")
      .def_readonly("log_config", &Grasp::log_config, "log C")
      .def_readonly("log_pregrasp", &Grasp::log_pregrasp, "log W of the pre-grasp configuration (clear_pregrasp)")
      .def_readonly("log_contact", &Grasp::log_contact, "log Q_i per query link (SynthesisResult.contact_links)")
      .def_readonly("log_experts", &Grasp::log_experts, "log E_k per expert (SynthesisResult.expert_names)")
      .def_readonly("optimised", &Grasp::optimised)
      .def("__repr__", [](const Grasp& g) {
        return "<Grasp log_likelihood=" + std::to_string(g.log_likelihood) + (g.optimised ? ", optimised>" : ">");
      });

  py::class_<SynthesisTiming>(m, "SynthesisTiming", "Seconds spent in each stage of synthesis.")
      .def_readonly("query", &SynthesisTiming::query, "s: query density estimation")
      .def_readonly("sampling", &SynthesisTiming::sampling, "s: sampling and ranking")
      .def_readonly("optimisation", &SynthesisTiming::optimisation, "s: annealing the best candidates")
      .def_readonly("total", &SynthesisTiming::total, "s")
      .def("__repr__", [](const SynthesisTiming& t) {
        return "SynthesisTiming(query=" + std::to_string(t.query) + ", sampling=" + std::to_string(t.sampling) +
               ", optimisation=" + std::to_string(t.optimisation) + ", total=" + std::to_string(t.total) + ")";
      });

  py::class_<SynthesisResult>(m, "SynthesisResult", "Grasps best first, with diagnostics.")
      .def_readonly("grasps", &SynthesisResult::grasps, "list of Grasp, best first")
      .def_readonly("contact_links", &SynthesisResult::contact_links)
      .def_readonly("expert_names", &SynthesisResult::expert_names)
      .def_readonly("evaluations", &SynthesisResult::evaluations, "grasps scored in all")
      .def_readonly("rejected", &SynthesisResult::rejected, "samples a hard constraint rejected")
      .def_readonly("timing", &SynthesisResult::timing, "SynthesisTiming")
      .def_property_readonly("term_names", &SynthesisResult::term_names,
                             "every term of log L, in the order of the columns' log_terms: collision, config, "
                             "pregrasp_clear, contact/<link> per query link, the experts")
      .def("columns", &grasp_columns,
           "The grasps' fields as arrays, one row a grasp (best first): {Grasp key: (N,) or (N, k)}; what "
           "result.grasps gives one grasp at a time, without a Python object per grasp and field");

  py::class_<Evaluation>(m, "Evaluation", "log L and its terms for a batch of grasps.")
      .def_readonly("total", &Evaluation::total, "(N,) log L")
      .def_readonly("log_collision", &Evaluation::log_collision, "(N,)")
      .def_readonly("log_config", &Evaluation::log_config, "(N,)")
      .def_readonly("log_pregrasp", &Evaluation::log_pregrasp, "(N,)")
      .def_readonly("log_contact", &Evaluation::log_contact, "(N, query links)")
      .def_readonly("log_experts", &Evaluation::log_experts, "(N, experts)");

  py::class_<QueryDensity>(m, "QueryDensity", "Q_i: one link's query density on an object.")
      .def_readonly("link", &QueryDensity::link)
      .def_readonly("link_name", &QueryDensity::link_name)
      .def_property_readonly("density",
                             [](const QueryDensity& q) { return std::const_pointer_cast<PoseDensity>(q.density); });

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
             const CollisionExpert& collision, const py::object& experts, const py::object& settings,
             const py::object& weights, const py::kwargs& kw) {
            const SynthesizerSettings s = settings_from<SynthesizerSettings>(settings, kw, "synthesize");
            const PoseArray v = to_poses(frames, "frames");
            const RowMatrixXd r = to_matrix(features, "features");
            const Eigen::VectorXd w = weights.is_none() ? Eigen::VectorXd() : to_vector(weights, "weights");
            const ExpertList e = to_experts(experts);
            py::gil_scoped_release release;
            return g.synthesize(v, r, collision, e, s, w);
          },
          py::arg("frames"), py::arg("features"), py::arg("collision"), py::arg("experts") = py::none(),
          py::arg("settings") = py::none(), py::kw_only(), py::arg("weights") = py::none(),
          ("Query densities, sampling, ranking and annealing on an object's frames (N, 7) and features (N, n);\n"
           "weights (N,): each point's prior weight in the query densities (None: all 1).\n" +
           settings_doc<SynthesizerSettings>())
              .c_str())
      .def(
          "query_densities",
          [](const GraspSynthesizer& g, const py::object& frames, const py::object& features,
             const py::object& settings, const py::object& seed, const py::object& weights, const py::kwargs& kw) {
            const QuerySettings s = settings_from<QuerySettings>(settings, kw, "query_densities");
            std::mt19937_64 rng(to_seed(seed));
            const PoseArray v = to_poses(frames, "frames");
            const RowMatrixXd r = to_matrix(features, "features");
            const Eigen::VectorXd w = weights.is_none() ? Eigen::VectorXd() : to_vector(weights, "weights");
            py::gil_scoped_release release;
            return g.query_densities(v, r, s, rng, w);
          },
          py::arg("frames"), py::arg("features"), py::arg("settings") = py::none(), py::arg("seed") = py::none(),
          py::kw_only(), py::arg("weights") = py::none(),
          ("The query densities Q_i on an object; weights (N,): each point's prior weight (None: all 1).\n" +
           settings_doc<QuerySettings>())
              .c_str())
      .def(
          "sample_grasps",
          [](const GraspSynthesizer& g, const std::vector<QueryDensity>& q, const py::object& n,
             const py::object& seed) {
            const int count = to_count(n, "sample_grasps: n", 0, kMaxDraws);
            std::mt19937_64 rng(to_seed(seed));
            PoseArray w;
            RowMatrixXd j;
            g.sample_grasps(q, count, rng, w, j);
            return py::make_tuple(w, j);
          },
          py::arg("query"), py::arg("n"), py::arg("seed") = py::none(), "(wrists (n, 7), joints (n, D)).")
      .def(
          "evaluate",
          [](const GraspSynthesizer& g, const std::vector<QueryDensity>& q, const CollisionExpert& collision,
             const py::object& experts, const py::object& wrists, const py::object& joints, const py::object& clear) {
            const bool clear_pregrasp = clear.is_none() ? SamplingSettings{}.clear_pregrasp : clear.cast<bool>();
            const auto expert_list = to_experts(experts);
            return g.evaluate(Scoring{q, collision, expert_list, clear_pregrasp}, to_poses(wrists, "wrists"),
                              to_configurations(g.hand(), joints, "joints"));
          },
          py::arg("query"), py::arg("collision"), py::arg("experts"), py::arg("wrists"), py::arg("joints"),
          py::arg("clear_pregrasp") = py::none(),
          "log L and its terms (an Evaluation) for a batch of grasps; clear_pregrasp=None: SamplingSettings' "
          "default.");
}

}  // namespace graspmix::py_bind
