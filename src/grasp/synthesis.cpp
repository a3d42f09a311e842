#include "graspmix/grasp/synthesis.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <typeinfo>

#include "graspmix/core/frame_jitter.hpp"
#include "graspmix/core/se3.hpp"
#include "graspmix/density/kde.hpp"
#include "graspmix/density/pose_mixture.hpp"

namespace graspmix {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// `rows` appended below `m` (the same number of columns).
template <typename M, typename R>
void append_rows(M& m, const R& rows) {
  const Eigen::Index n = m.rows();
  m.conservativeResize(n + rows.rows(), Eigen::NoChange);
  m.bottomRows(rows.rows()) = rows;
}

/// Index of a draw from unnormalised log weights (all -inf: uniform).
std::discrete_distribution<int> distribution_from_logs(const Eigen::VectorXd& logw) {
  const double m = logw.maxCoeff();
  Eigen::VectorXd p = std::isfinite(m) ? Eigen::VectorXd((logw.array() - m).exp()) : Eigen::VectorXd::Ones(logw.size());
  return std::discrete_distribution<int>(p.data(), p.data() + p.size());
}

/// Builds the query density Q_i of the same kind as a contact model's density (eq:query_density_approx):
/// a mixture fitted by EM (its seed drawn from rng) for a mixture, a KDE for a KDE.
class QueryDensityOfKind final : public PoseDensityVisitor {
 public:
  QueryDensityOfKind(const QuerySettings& s, std::mt19937_64& rng) : s_(s), rng_(rng) {}
  void operator()(const PoseMixture&) override {
    GmmSettings g;
    g.n_components = s_.n_components;
    g.max_iter = s_.max_iter;
    g.reg_covar = s_.reg_covar;
    g.seed = rng_();
    density = std::make_shared<PoseMixture>(g);
  }
  void operator()(const PoseKDE&) override { density = std::make_shared<PoseKDE>(s_.kde); }

  std::shared_ptr<PoseDensity> density;

 private:
  const QuerySettings& s_;
  std::mt19937_64& rng_;
};

}  // namespace

GraspSynthesizer::GraspSynthesizer(std::shared_ptr<const Hand> hand, std::vector<ContactModel> contact_models,
                                   ConfigModel config)
    : hand_(std::move(hand)), contact_models_(std::move(contact_models)), config_(std::move(config)) {
  if (!hand_) throw std::invalid_argument("GraspSynthesizer: no hand");
  if (contact_models_.empty()) throw std::invalid_argument("GraspSynthesizer: no contact models");
  require_config_of(config_, *hand_, "GraspSynthesizer");
  for (const ContactModel& m : contact_models_) {
    if (!m.density || !m.density->fitted())
      throw std::invalid_argument("GraspSynthesizer: contact model of link '" + m.link_name + "' is not fitted");
    if (m.link < 0 || m.link >= hand_->n_links() || hand_->link_names()[m.link] != m.link_name) {
      throw std::invalid_argument("GraspSynthesizer: contact model link '" + m.link_name + "' is not link " +
                                  std::to_string(m.link) + " of hand '" + hand_->name() + "'");
    }
    if (typeid(*m.density) != typeid(*contact_models_.front().density)) {
      throw std::invalid_argument("GraspSynthesizer: contact models mix GMM and KDE densities");
    }
    for (const ContactModel& other : contact_models_) {
      if (&other != &m && other.link == m.link) {
        throw std::invalid_argument("GraspSynthesizer: two contact models for link '" + m.link_name + "'");
      }
    }
  }
}

std::string GraspSynthesizer::method() const { return contact_models_.front().density->kind(); }

std::vector<QueryDensity> GraspSynthesizer::query_densities(const Eigen::Ref<const PoseArray>& frames,
                                                            const Eigen::Ref<const RowMatrixXd>& features,
                                                            const QuerySettings& s, std::mt19937_64& rng,
                                                            const Eigen::Ref<const Eigen::VectorXd>& weights) const {
  if (frames.rows() == 0) throw std::invalid_argument("query densities: the object has no surface points");
  if (weights.size() != 0) {
    if (weights.size() != frames.rows()) {
      throw std::invalid_argument("query densities: " + std::to_string(frames.rows()) + " frames but " +
                                  std::to_string(weights.size()) + " weights");
    }
    if (!weights.allFinite() || (weights.array() < 0).any() || !(weights.maxCoeff() > 0)) {
      throw std::invalid_argument("query densities: weights must be finite, >= 0 and not all 0");
    }
  }
  const Eigen::VectorXd log_weights =
      weights.size() ? Eigen::VectorXd(weights.array().log()) : Eigen::VectorXd::Zero(frames.rows());
  if (features.rows() != frames.rows()) {
    throw std::invalid_argument("query densities: " + std::to_string(frames.rows()) + " frames but " +
                                std::to_string(features.rows()) + " feature rows");
  }
  if (s.n_samples < std::max(2, s.n_components)) {
    throw std::invalid_argument("query densities: n_samples must be at least n_components and 2");
  }
  if (s.link_floor && !std::isfinite(*s.link_floor)) {
    throw std::invalid_argument("query densities: link_floor must be finite or unset");
  }
  require_finite(frames, "query densities: frames");
  require_finite(features, "query densities: features");
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  std::vector<PoseArray> samples;
  std::vector<std::shared_ptr<PoseDensity>> densities;
  for (const ContactModel& m : contact_models_) {
    // Importance resampling: surface points in proportion to M_i(r).
    auto pick = distribution_from_logs(m.density->feature_log_density(features) + log_weights);
    PoseArray v(s.n_samples, 7);
    RowMatrixXd r(s.n_samples, features.cols());
    for (int k = 0; k < s.n_samples; ++k) {
      const int j = pick(rng);
      v.row(k) = frames.row(j);
      r.row(k) = features.row(j);
      if (s.frame_jitter && features.cols() >= 2) {
        const double k1 = features(j, 0), k2 = features(j, 1);
        const double rel = k1 > 1e-12 ? (k1 - k2) / k1 : 0.0;
        const double angle = frame_jitter_angle(rel, s.jitter_sharpness, uni(rng));
        const Eigen::Quaterniond q =
            row_quaternion(v, k).normalized() * Eigen::Quaterniond(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()));
        v.row(k).tail<4>() << q.x(), q.y(), q.z(), q.w();
      }
    }
    const PoseArray u = m.density->sample(r, rng);
    samples.push_back(pose_multiply(v, u));  // s = v o u
    QueryDensityOfKind kind(s, rng);
    m.density->accept(kind);
    densities.push_back(std::move(kind.density));
  }
  // The fits draw from their own seeds (drawn above, in link order): one thread per link, the same densities.
  const int n_links = static_cast<int>(densities.size());
  std::vector<std::exception_ptr> errors(densities.size());
#pragma omp parallel for schedule(dynamic, 1) if (n_links > 1)
  for (int l = 0; l < n_links; ++l) {
    try {
      densities[l]->fit(samples[l], RowMatrixXd(s.n_samples, 0), {});
    } catch (...) {
      errors[l] = std::current_exception();  // rethrown below, outside the threads
    }
  }
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
  std::vector<QueryDensity> out;
  for (size_t l = 0; l < densities.size(); ++l) {
    out.push_back({contact_models_[l].link, contact_models_[l].link_name, std::move(densities[l]), s.link_floor});
  }
  return out;
}

void GraspSynthesizer::sample_grasps(const std::vector<QueryDensity>& query, int n, std::mt19937_64& rng,
                                     PoseArray& wrists, RowMatrixXd& joints) const {
  if (query.empty()) throw std::invalid_argument("sample_grasps: no query densities");
  if (n < 0) throw std::invalid_argument("sample_grasps: n must be >= 0");
  joints = config_.sample(n, rng);
  wrists.resize(n, 7);
  std::uniform_int_distribution<int> which(0, static_cast<int>(query.size()) - 1);
  std::vector<int> link_of(n);
  for (int i = 0; i < n; ++i) link_of[i] = which(rng);
  std::vector<Eigen::Isometry3d> links(hand_->n_links());
  for (size_t l = 0; l < query.size(); ++l) {
    std::vector<int> rows;
    for (int i = 0; i < n; ++i)
      if (link_of[i] == static_cast<int>(l)) rows.push_back(i);
    if (rows.empty()) continue;
    const PoseArray s = query[l].density->sample(RowMatrixXd(rows.size(), 0), rng);
    for (size_t k = 0; k < rows.size(); ++k) {
      const int i = rows[k];
      hand_->fk_into(Eigen::Isometry3d::Identity(), joints.row(i).data(), links.data());
      const Eigen::Isometry3d T_world_link = pose_from_vector(s.row(k).transpose());
      wrists.row(i) = pose_to_vector(T_world_link * links[query[l].link].inverse()).transpose();
    }
  }
}

Eigen::VectorXd Grasp::log_terms() const {
  Eigen::VectorXd t(3 + log_contact.size() + log_experts.size());
  t << log_collision, log_config, log_pregrasp, log_contact, log_experts;
  return t;
}

std::vector<std::string> SynthesisResult::term_names() const {
  std::vector<std::string> names = {kCollisionTerm, kConfigTerm, kPregraspTerm};
  for (const std::string& link : contact_links) names.push_back(kContactTermPrefix + link);
  names.insert(names.end(), expert_names.begin(), expert_names.end());
  return names;
}

namespace {

/// dst's rows `to` = src's rows `from` (same length).
void copy_rows(const Evaluation& src, const std::vector<Eigen::Index>& from, Evaluation& dst,
               const std::vector<Eigen::Index>& to) {
  for (size_t k = 0; k < from.size(); ++k) {
    const Eigen::Index i = from[k], j = to[k];
    dst.total[j] = src.total[i];
    dst.log_collision[j] = src.log_collision[i];
    dst.log_config[j] = src.log_config[i];
    dst.log_pregrasp[j] = src.log_pregrasp[i];
    dst.log_contact.row(j) = src.log_contact.row(i);
    dst.log_experts.row(j) = src.log_experts.row(i);
  }
}

/// An evaluation of n grasps over n_contact links and n_experts experts, to be filled.
Evaluation empty_evaluation(Eigen::Index n, Eigen::Index n_contact, Eigen::Index n_experts) {
  Evaluation e;
  e.total.resize(n);
  e.log_collision.resize(n);
  e.log_config.resize(n);
  e.log_pregrasp.resize(n);
  e.log_contact.resize(n, n_contact);
  e.log_experts.resize(n, n_experts);
  return e;
}

/// Indices best first; NaN (never expected: evaluate rejects it) ranks with -inf, ties keep their order.
std::vector<int> rank_best_first(const Eigen::VectorXd& total) {
  std::vector<int> order(total.size());
  std::iota(order.begin(), order.end(), 0);
  auto key = [&](int i) { return std::isnan(total[i]) ? -std::numeric_limits<double>::infinity() : total[i]; };
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return key(a) > key(b); });
  return order;
}

void check_expert_names(const std::vector<std::shared_ptr<const Expert>>& experts) {
  std::vector<std::string> seen;
  for (const auto& e : experts) {
    if (!e) throw std::invalid_argument("synthesize: an expert is null");
    const std::string n = e->name();
    if (n == kCollisionTerm || n == kConfigTerm || n == kPregraspTerm || n.rfind(kContactTermPrefix, 0) == 0) {
      throw std::invalid_argument("synthesize: expert name '" + n + "' is reserved for a built-in term");
    }
    if (std::find(seen.begin(), seen.end(), n) != seen.end()) {
      throw std::invalid_argument("synthesize: two experts are named '" + n + "'; names key the grasps' expert table");
    }
    seen.push_back(n);
  }
}

}  // namespace

GraspSynthesizer::Candidates GraspSynthesizer::sample_passing(const Scoring& scoring, const SynthesizerSettings& s,
                                                              std::mt19937_64& rng, SynthesisResult& res) const {
  std::vector<PoseArray> batch_w;
  std::vector<RowMatrixXd> batch_q;
  std::vector<Evaluation> batch_e;
  std::vector<std::pair<int, Eigen::Index>> passed, rejected;  // (batch, row)
  const int n = s.sampling.n_samples * s.sampling.oversample;  // checked by synthesize: no overflow
  for (int round = 0; round < s.sampling.max_sampling_rounds && static_cast<int>(passed.size()) < n; ++round) {
    PoseArray w;
    RowMatrixXd q;
    sample_grasps(scoring.query, n, rng, w, q);
    batch_e.push_back(evaluate(scoring, w, q));
    batch_w.push_back(std::move(w));
    batch_q.push_back(std::move(q));
    res.evaluations += n;
    const Evaluation& e = batch_e.back();
    for (Eigen::Index i = 0; i < e.total.size(); ++i) {
      if (e.total[i] > -std::numeric_limits<double>::infinity()) {
        if (static_cast<int>(passed.size()) < n) passed.emplace_back(round, i);
      } else {
        ++res.rejected;
        rejected.emplace_back(round, i);
      }
    }
  }
  // Too few passed: rejected samples fill up (ranked last; still optimised if among the best).
  for (size_t k = 0; static_cast<int>(passed.size()) < n && k < rejected.size(); ++k) passed.push_back(rejected[k]);
  Candidates c;
  const Eigen::Index kept = static_cast<Eigen::Index>(passed.size());
  c.wrists.resize(kept, 7);
  c.joints.resize(kept, hand_->n_dofs());
  c.eval = empty_evaluation(kept, scoring.query.size(), scoring.experts.size());
  for (Eigen::Index k = 0; k < kept; ++k) {
    const auto [b, i] = passed[k];
    c.wrists.row(k) = batch_w[b].row(i);
    c.joints.row(k) = batch_q[b].row(i);
    copy_rows(batch_e[b], {i}, c.eval, {k});
  }
  return c;
}

void GraspSynthesizer::add_seeds(const Scoring& scoring, const SeedGrasps& seeds, Candidates& c,
                                 SynthesisResult& res) const {
  require_joints_shape(seeds.wrists.rows(), seeds.joints, hand_->n_dofs(), "synthesize: seeds");
  const Evaluation e = evaluate(scoring, seeds.wrists, seeds.joints);
  res.evaluations += static_cast<int>(seeds.wrists.rows());
  append_rows(c.wrists, seeds.wrists);
  append_rows(c.joints, seeds.joints);
  append_rows(c.eval.total, e.total);
  append_rows(c.eval.log_collision, e.log_collision);
  append_rows(c.eval.log_config, e.log_config);
  append_rows(c.eval.log_pregrasp, e.log_pregrasp);
  append_rows(c.eval.log_contact, e.log_contact);
  append_rows(c.eval.log_experts, e.log_experts);
}

std::vector<bool> GraspSynthesizer::optimise_best(const Scoring& scoring, const SynthesizerSettings& s,
                                                  const std::vector<int>& order, std::mt19937_64& rng, Candidates& c,
                                                  SynthesisResult& res) const {
  std::vector<bool> optimised(c.wrists.rows(), false);
  const int n_opt = s.sampling.optimise ? std::min<int>(s.sampling.n_optimise, static_cast<int>(c.wrists.rows())) : 0;
  if (n_opt == 0) return optimised;
  std::vector<Eigen::Index> rows(order.begin(), order.begin() + n_opt);
  PoseArray w(n_opt, 7);
  RowMatrixXd q(n_opt, c.joints.cols());
  for (int k = 0; k < n_opt; ++k) {
    w.row(k) = c.wrists.row(rows[k]);
    q.row(k) = c.joints.row(rows[k]);
  }
  res.evaluations += anneal(scoring, s.annealing, rng, w, q);
  const Evaluation e = evaluate(scoring, w, q);
  res.evaluations += n_opt;
  for (int k = 0; k < n_opt; ++k) {
    c.wrists.row(rows[k]) = w.row(k);
    c.joints.row(rows[k]) = q.row(k);
    optimised[rows[k]] = true;
  }
  std::vector<Eigen::Index> all(n_opt);
  std::iota(all.begin(), all.end(), 0);
  copy_rows(e, all, c.eval, rows);
  return optimised;
}

SynthesisResult GraspSynthesizer::synthesize(
    const Eigen::Ref<const PoseArray>& frames, const Eigen::Ref<const RowMatrixXd>& features,
    const CollisionExpert& collision, const std::vector<std::shared_ptr<const Expert>>& experts,
    const SynthesizerSettings& s, const Eigen::Ref<const Eigen::VectorXd>& weights, const SeedGrasps* seeds) const {
  if (s.sampling.n_samples < 1) throw std::invalid_argument("synthesize: n_samples must be >= 1");
  if (s.sampling.oversample < 1 || s.sampling.oversample > kMaxOversample ||
      s.sampling.n_samples > std::numeric_limits<int>::max() / s.sampling.oversample)
    throw std::invalid_argument("synthesize: oversample must be in [1, " + std::to_string(kMaxOversample) +
                                "] and oversample * n_samples an int");
  if (s.sampling.n_optimise < 0) throw std::invalid_argument("synthesize: n_optimise must be >= 0");
  if (s.sampling.max_sampling_rounds < 1) throw std::invalid_argument("synthesize: max_sampling_rounds must be >= 1");
  if (collision.hand().name() != hand_->name() || collision.hand().link_names() != hand_->link_names()) {
    throw std::invalid_argument("synthesize: the collision expert was built for hand '" + collision.hand().name() +
                                "', the model for '" + hand_->name() + "'");
  }
  check_expert_names(experts);
  const auto t0 = std::chrono::steady_clock::now();
  std::mt19937_64 rng(s.seed);
  SynthesisResult res;
  const std::vector<QueryDensity> query = query_densities(frames, features, s.query, rng, weights);
  res.timing.query = seconds_since(t0);

  const auto t1 = std::chrono::steady_clock::now();
  const Scoring scoring{query, collision, experts, s.sampling.clear_pregrasp};
  Candidates c = sample_passing(scoring, s, rng, res);
  if (seeds && seeds->wrists.rows() > 0) add_seeds(scoring, *seeds, c, res);
  std::vector<int> order = rank_best_first(c.eval.total);
  res.timing.sampling = seconds_since(t1);

  const auto t2 = std::chrono::steady_clock::now();
  const std::vector<bool> optimised = optimise_best(scoring, s, order, rng, c, res);
  if (s.sampling.optimise) order = rank_best_first(c.eval.total);
  res.timing.optimisation = seconds_since(t2);

  for (const QueryDensity& q : query) res.contact_links.push_back(q.link_name);
  for (const auto& e : experts) res.expert_names.push_back(e->name());
  // The best n_samples of the drawn grasps (oversample times as many) and the seeds.
  if (order.size() > static_cast<size_t>(s.sampling.n_samples)) order.resize(static_cast<size_t>(s.sampling.n_samples));
  res.grasps.reserve(order.size());
  for (int i : order) {
    Grasp g;
    g.T_world_wrist = c.wrists.row(i).transpose();
    g.joints = c.joints.row(i).transpose();
    g.pregrasp = config_.pregrasp_for(g.joints);
    g.log_likelihood = c.eval.total[i];
    g.log_collision = c.eval.log_collision[i];
    g.log_config = c.eval.log_config[i];
    g.log_pregrasp = c.eval.log_pregrasp[i];
    g.log_contact = c.eval.log_contact.row(i).transpose();
    g.log_experts = c.eval.log_experts.row(i).transpose();
    g.optimised = optimised[i];
    res.grasps.push_back(std::move(g));
  }
  res.timing.total = seconds_since(t0);
  return res;
}

}  // namespace graspmix
