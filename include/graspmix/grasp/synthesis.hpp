#pragma once
// Grasp synthesis for a novel object (sections "Grasp synthesis for novel objects" and "Grasp
// optimisation" of the paper), identical for both methods but for the density type:
//   1. contact query densities Q_i (eq:query_density_approx): sample surface frames v with probability
//      proportional to M_i(r) (importance resampling of the paper's weights w = M_i(r); times each point's
//      prior weight where one is given: completed points the camera did not see weigh less), draw
//      u ~ M_i(u | r), form s = v o u, and fit a PoseMixture with K_Q components (GMM models) or a PoseKDE
//      with one kernel per sample (KDE models);
//   2. grasp sampling: a link pose s ~ Q_i for a random link i, joints h_c ~ C, the wrist through fk;
//   3. ranking by log L(h) = log W + log C + sum_i log Q_i(fk_i(h)) + sum_k log E_k
//      (eq:opt_criterion_extended);
//   4. simulated annealing of the best candidates with the paper's schedule (temperature falling
//      linearly from its initial value over the iterations).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "graspmix/core/frame_jitter.hpp"
#include "graspmix/density/gmm.hpp"
#include "graspmix/density/kde.hpp"
#include "graspmix/density/pose_density.hpp"
#include "graspmix/grasp/collision.hpp"
#include "graspmix/grasp/config_model.hpp"
#include "graspmix/grasp/contact_model.hpp"
#include "graspmix/grasp/experts.hpp"
#include "graspmix/robot/hand.hpp"

namespace graspmix {

struct QuerySettings {
  int n_samples = 500;   ///< N_Q: samples per link to fit each query density from
  int n_components = 5;  ///< K_Q for GMM models
  int max_iter = 100;    ///< EM iterations of the query mixtures
  double reg_covar = 1e-6;
  KdeSettings kde;  ///< kernels of KDE query densities (features unused)
  /// Rotate each sampled surface frame about its normal by a random angle of size
  /// pi * exp(-jitter_sharpness ((k1 - k2) / k1)^2) (Kopicki's rule): where k1 ~ k2 the first principal
  /// direction is arbitrary, so the frame's heading carries no information. Needs features [k1, k2].
  bool frame_jitter = true;
  double jitter_sharpness = kKopickiJitterSharpness;
  /// The prior weight of a completed point (one the cameras did not see: perception/completion.hpp) in the query
  /// densities, an observed point's being 1; in (0, 1]. The scene synthesis passes it as query_densities'
  /// weights. 1: on the development objects (one view, clutter_dev) 0.25 and 0.5 lifted no more than 1
  /// (docs/one-view.md), so a completed surface counts as much as a seen one unless a user says otherwise.
  double completed_weight = 1.0;
  /// nats: each link's contact term is scored as log(Q_i(pose) + exp(link_floor)), its query density mixed with a
  /// flat one (contact_log_term), so that a link that finds nothing like the surface it touched in the demonstration
  /// costs at most a bounded amount and does not outweigh the others: on a flat object one WSG 50 finger's term
  /// fell to -160 to -1750 nats and ranked grasps by which was least far from it. Unset: the densities as they are
  /// (the paper's product; SynthesisOptions.paper()). -20: chosen on the development sets, one view, GMM: test60
  /// 91.2 -> 94.0% (+23 / -6), a named object in packed clutter_dev scenes 86.2 -> 95.0% (docs/one-view.md, "A
  /// floor under each link's contact term"); a link where its density is high scores within 1e-8 nats of it.
  std::optional<double> link_floor = -20.0;
};

struct AnnealingSettings {
  int iterations = 100;              ///< the paper's 100
  double initial_temperature = 1.0;  ///< the paper's 1.0, falling linearly to 0
  double position_step = 0.005;      ///< m: std of wrist translation proposals at temperature 1
  double rotation_step = 0.1;        ///< rad: std of wrist rotation proposals at temperature 1
  double joint_step = 0.5;  ///< std of joint proposals at temperature 1, in units of the config model's kernel std
};

/// The largest SamplingSettings::oversample.
inline constexpr int kMaxOversample = 100;

/// How many grasps are drawn, kept and annealed.
struct SamplingSettings {
  int n_samples = 200;  ///< grasps sampled, ranked and returned
  /// oversample * n_samples grasps that pass the hard experts are drawn (batches of that many), ranked with the
  /// seeds, the best n_optimise of them annealed, and the best n_samples returned: a wider search for the same
  /// result's size. 1: the paper's. 2: one view, GMM, a named object in packed scenes, development 661 -> 686 of 800
  /// (+67 / -42) and 664 -> 673 on a second set of scenes, held out 717 -> 727; single development objects 283 ->
  /// 285 of 300; the sampling stage's cost doubles, the annealing's does not change (docs/one-view.md, "Twice the
  /// samples drawn").
  int oversample = 2;
  int n_optimise = 10;  ///< the best this many are optimised
  bool optimise = true;
  /// An extra collision expert on the grasp's pre-grasp configuration (the hand starts there, so a
  /// pre-grasp in collision cannot be executed): log W of the opened hand, soft like W itself.
  bool clear_pregrasp = true;
  /// Hard constraints act by rejection sampling (the paper's definition): batches of n_samples are drawn
  /// until n_samples grasps pass them all, for at most this many batches; the rest are then kept rejected.
  int max_sampling_rounds = 10;
  /// Scene synthesis adds each object's top-down seeds (grasp/topdown_seeds.hpp) to the drawn grasps: scored,
  /// ranked and annealed with them, the worst of all dropped so that n_samples remain. One view, GMM, development sets:
  /// test60 88.2 -> 91.2% (+23 / -5), clutter_dev 90.7 -> 92.7% (+8 / -2) (docs/one-view.md, "Top-down seeds"). Off in
  /// the paper's preset.
  bool topdown_seeds = true;
};

/// Grasps a caller proposes to the synthesiser besides the drawn ones (GraspSynthesizer::synthesize's `seeds`; e.g.
/// grasp/topdown_seeds.hpp): wrist poses (N, 7) and configurations (N, D).
struct SeedGrasps {
  PoseArray wrists;
  RowMatrixXd joints;
};

/// Everything GraspSynthesizer::synthesize needs besides the object and the experts.
struct SynthesizerSettings {
  SamplingSettings sampling;
  QuerySettings query;
  AnnealingSettings annealing;
  std::uint64_t seed = 0;  ///< seeds everything random in synthesis
};

struct Grasp {
  Eigen::Matrix<double, 7, 1> T_world_wrist;
  Eigen::VectorXd joints;    ///< grasp configuration h_c (Hand::joint_names() order)
  Eigen::VectorXd pregrasp;  ///< the configuration to approach with
  double log_likelihood = 0.0;
  double log_collision = 0.0;   ///< log W
  double log_config = 0.0;      ///< log C
  double log_pregrasp = 0.0;    ///< log W of the pre-grasp configuration (clear_pregrasp)
  Eigen::VectorXd log_contact;  ///< log Q_i per query link (SynthesisResult::contact_links)
  Eigen::VectorXd log_experts;  ///< log E_k per expert (SynthesisResult::expert_names)
  bool optimised = false;
  /// log W, log C, the pre-grasp's log W, the log Q_i, the log E_k: the terms of SynthesisResult::term_names().
  Eigen::VectorXd log_terms() const;
};

struct SynthesisTiming {
  double query = 0.0;         ///< s: query density estimation
  double sampling = 0.0;      ///< s: sampling and ranking
  double optimisation = 0.0;  ///< s: annealing the best candidates
  double total = 0.0;
};

/// The names of the built-in terms of log L in a grasp's table of terms; no expert may take them. Each query
/// link's Q_i is kContactTermPrefix + its link name.
inline constexpr const char* kCollisionTerm = "collision";
inline constexpr const char* kConfigTerm = "config";
inline constexpr const char* kPregraspTerm = "pregrasp_clear";
inline constexpr const char* kContactTermPrefix = "contact/";

struct SynthesisResult {
  std::vector<Grasp> grasps;  ///< best first
  std::vector<std::string> contact_links;
  std::vector<std::string> expert_names;
  /// Every term's name in the order of Grasp::log_terms(): collision, config, pregrasp_clear, each query
  /// link's "contact/<link>", then the experts'.
  std::vector<std::string> term_names() const;
  SynthesisTiming timing;
  int evaluations = 0;  ///< grasps scored in all
  int rejected = 0;     ///< samples a hard constraint rejected (rejection sampling)
};

/// One link's query density Q_i.
struct QueryDensity {
  int link = -1;
  std::string link_name;
  std::shared_ptr<const PoseDensity> density;
  std::optional<double> floor;  ///< QuerySettings::link_floor: the link's term is contact_log_term(log Q, floor)
};

/// A link's contact term from its query density's log value: log(exp(log_q) + exp(floor)), or log_q without a floor.
inline double contact_log_term(double log_q, const std::optional<double>& floor) {
  if (!floor) return log_q;
  const double hi = std::max(log_q, *floor), lo = std::min(log_q, *floor);
  return hi + std::log1p(std::exp(lo - hi));
}

/// What a grasp is scored against (eq:opt_criterion_extended): the query densities Q_i, the collision expert W,
/// the other experts E_k in their order, and whether W is also charged at the pre-grasp (SamplingSettings::
/// clear_pregrasp). It refers to them; they must outlive it.
struct Scoring {
  const std::vector<QueryDensity>& query;
  const CollisionExpert& collision;
  const std::vector<std::shared_ptr<const Expert>>& experts;
  bool clear_pregrasp = SamplingSettings{}.clear_pregrasp;
};

/// Log-likelihood terms of a batch of grasps.
struct Evaluation {
  Eigen::VectorXd total, log_collision, log_config, log_pregrasp;
  RowMatrixXd log_contact;  ///< (N, n query links)
  RowMatrixXd log_experts;  ///< (N, n experts)
};

class GraspSynthesizer {
 public:
  GraspSynthesizer(std::shared_ptr<const Hand> hand, std::vector<ContactModel> contact_models, ConfigModel config);

  /// Everything: query densities on the object (frames (N, 7), features (N, n), each point's prior weight
  /// (N), empty: all 1), sampling, ranking, optimisation. The collision expert is built on the same object's
  /// cloud (and support plane). seeds: grasps the caller proposes (e.g. topdown_seeds), scored and ranked with the
  /// drawn ones and annealed if among the best; the best n_samples of them all are returned.
  SynthesisResult synthesize(const Eigen::Ref<const PoseArray>& frames, const Eigen::Ref<const RowMatrixXd>& features,
                             const CollisionExpert& collision,
                             const std::vector<std::shared_ptr<const Expert>>& experts,
                             const SynthesizerSettings& settings,
                             const Eigen::Ref<const Eigen::VectorXd>& weights = Eigen::VectorXd(),
                             const SeedGrasps* seeds = nullptr) const;

  // ---- the stages, for tests, benchmarks and custom pipelines ----
  /// The surface points are drawn in proportion to weights[j] M_i(r_j): weights (N) >= 0, finite, not all 0 (a
  /// completed point the camera did not see weighs less than an observed one); empty: all 1.
  std::vector<QueryDensity> query_densities(const Eigen::Ref<const PoseArray>& frames,
                                            const Eigen::Ref<const RowMatrixXd>& features,
                                            const QuerySettings& settings, std::mt19937_64& rng,
                                            const Eigen::Ref<const Eigen::VectorXd>& weights = Eigen::VectorXd()) const;
  /// n grasps: wrists (n, 7) and joints (n, D).
  void sample_grasps(const std::vector<QueryDensity>& query, int n, std::mt19937_64& rng, PoseArray& wrists,
                     RowMatrixXd& joints) const;
  Evaluation evaluate(const Scoring& scoring, const Eigen::Ref<const PoseArray>& wrists,
                      const Eigen::Ref<const RowMatrixXd>& joints) const;
  /// Anneals every row of (wrists, joints) in place; returns the evaluations spent. Its random numbers are drawn
  /// from rng first; blocks of chains then run on OpenMP threads when every expert scores in parts
  /// (Expert::scores_in_parts), with the same result as on one thread.
  int anneal(const Scoring& scoring, const AnnealingSettings& settings, std::mt19937_64& rng, PoseArray& wrists,
             RowMatrixXd& joints) const;

  const Hand& hand() const { return *hand_; }
  const std::shared_ptr<const Hand>& hand_ptr() const { return hand_; }
  const std::vector<ContactModel>& contact_models() const { return contact_models_; }
  const ConfigModel& config_model() const { return config_; }
  /// "gmm" or "kde": the density type of the contact models.
  std::string method() const;

 private:
  /// Whether grasp i's proposal is refused whatever its last expert says, given `bound`, an upper bound of its
  /// log L (the other terms and the last expert's max_log_value).
  using Settled = std::function<bool(Eigen::Index i, double bound)>;
  /// evaluate(); with `settled`, the last expert, when it has a finite max_log_value, is scored after the other
  /// terms and only on the grasps `settled` leaves open (the others get total -inf and that term NaN).
  Evaluation evaluate_bounded(const Scoring& scoring, const Eigen::Ref<const PoseArray>& wrists,
                              const Eigen::Ref<const RowMatrixXd>& joints, const Settled& settled) const;
  /// anneal()'s random numbers (scoring.cpp)
  struct AnnealingNoise;
  /// anneal()'s chains `first`.. (the rows of wrists and joints) with their numbers of `noise`.
  void anneal_chains(const Scoring& scoring, const AnnealingSettings& s, const AnnealingNoise& noise,
                     Eigen::Index first, PoseArray& wrists, RowMatrixXd& joints) const;
  /// Grasps with their evaluation, rows aligned.
  struct Candidates {
    PoseArray wrists;
    RowMatrixXd joints;
    Evaluation eval;
  };
  /// Rejection sampling: batches of settings.n_samples until that many pass the hard experts (at most
  /// max_sampling_rounds batches; then rejected samples fill up). Counts evaluations and rejections.
  Candidates sample_passing(const Scoring& scoring, const SynthesizerSettings& s, std::mt19937_64& rng,
                            SynthesisResult& res) const;
  /// Scores the seeds and appends them to the candidates.
  void add_seeds(const Scoring& scoring, const SeedGrasps& seeds, Candidates& c, SynthesisResult& res) const;
  /// Anneals the best n_optimise candidates in place (rows `order[0..]`), re-scoring only those.
  std::vector<bool> optimise_best(const Scoring& scoring, const SynthesizerSettings& s, const std::vector<int>& order,
                                  std::mt19937_64& rng, Candidates& c, SynthesisResult& res) const;

  std::shared_ptr<const Hand> hand_;
  std::vector<ContactModel> contact_models_;
  ConfigModel config_;
};

}  // namespace graspmix
