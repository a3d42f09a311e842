#include "graspmix/grasp/synthesis.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <tuple>
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

/// Index of a draw from unnormalised log weights (all -inf: uniform).
std::discrete_distribution<int> distribution_from_logs(const Eigen::VectorXd& logw) {
  const double m = logw.maxCoeff();
  Eigen::VectorXd p = std::isfinite(m) ? Eigen::VectorXd((logw.array() - m).exp()) : Eigen::VectorXd::Ones(logw.size());
  return std::discrete_distribution<int>(p.data(), p.data() + p.size());
}

Eigen::Quaterniond quat_row(const Eigen::Ref<const PoseArray>& a, Eigen::Index i) {
  return Eigen::Quaterniond(a(i, 6), a(i, 3), a(i, 4), a(i, 5)).normalized();
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
            quat_row(v, k) * Eigen::Quaterniond(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()));
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
    out.push_back({contact_models_[l].link, contact_models_[l].link_name, std::move(densities[l])});
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

Evaluation GraspSynthesizer::evaluate(const Scoring& scoring, const Eigen::Ref<const PoseArray>& wrists,
                                      const Eigen::Ref<const RowMatrixXd>& joints) const {
  return evaluate_bounded(scoring, wrists, joints, nullptr);
}

Evaluation GraspSynthesizer::evaluate_bounded(const Scoring& scoring, const Eigen::Ref<const PoseArray>& wrists_in,
                                              const Eigen::Ref<const RowMatrixXd>& joints_in,
                                              const Settled& settled) const {
  const auto& [query, collision, experts, clear_pregrasp] = scoring;
  const Eigen::Index n = wrists_in.rows();
  require_joints_shape(n, joints_in, hand_->n_dofs(), "evaluate");
  const PoseArray wrists = wrists_in;
  const RowMatrixXd joints = joints_in;
  // Bad rows fail here, named by the caller's row, before any expert or subset sees them.
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!wrists.row(i).allFinite() || !(wrists.row(i).tail<4>().norm() > 1e-12)) {
      throw std::invalid_argument("evaluate: wrist pose " + std::to_string(i) +
                                  " is not finite or has a zero quaternion");
    }
  }
  require_finite(joints, "evaluate: joints");
  // The experts first (evaluate_experts): a grasp a hard expert rejects costs nothing more (its other terms
  // stay NaN, "not evaluated"), which keeps rejection sampling cheap. A bounded last expert (settled) waits for
  // the other terms, which may make it unnecessary.
  const bool deferred = settled && !experts.empty() && std::isfinite(experts.back()->max_log_value());
  const std::vector<std::shared_ptr<const Expert>> first(experts.begin(), experts.end() - (deferred ? 1 : 0));
  ExpertTerms terms = evaluate_experts(first, wrists, joints);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Evaluation e;
  e.log_experts = RowMatrixXd::Constant(n, static_cast<Eigen::Index>(experts.size()), nan);
  e.log_experts.leftCols(static_cast<Eigen::Index>(first.size())) = terms.log_values;
  e.total = std::move(terms.total);
  const std::vector<Eigen::Index>& alive = terms.passed;
  const Eigen::Index m = static_cast<Eigen::Index>(alive.size());
  const auto [w, q] = batch_rows(wrists, joints, alive);
  e.log_contact = RowMatrixXd::Constant(n, query.size(), nan);
  e.log_config = e.log_collision = e.log_pregrasp = Eigen::VectorXd::Constant(n, nan);
  if (m == 0) return e;
  const RowMatrixXd link_poses = hand_->fk_batch(w, q);
  RowMatrixXd contact(m, query.size());
  for (size_t l = 0; l < query.size(); ++l) {
    const PoseArray P = link_poses.middleCols(7 * query[l].link, 7);
    contact.col(l) = query[l].density->log_density(P, RowMatrixXd(m, 0));
  }
  const Eigen::VectorXd config = config_.log_density(q);
  Eigen::VectorXd coll, pre_w = Eigen::VectorXd::Zero(m);
  if (clear_pregrasp) {
    // One pass: the links the pre-grasp leaves in place (the palm) are scored once.
    std::tie(coll, pre_w) = collision.log_w_pair(w, q, config_.pregrasps_for(q));
  } else {
    coll = collision.evaluate_batch(w, q).log_w;
  }
  Eigen::VectorXd rest(m);  // each grasp's terms but the experts', summed as the total has always summed them
  for (Eigen::Index k = 0; k < m; ++k) {
    const Eigen::Index i = alive[k];
    e.log_contact.row(i) = contact.row(k);
    e.log_config[i] = config[k];
    e.log_collision[i] = coll[k];
    e.log_pregrasp[i] = pre_w[k];
    rest[k] = coll[k] + config[k] + pre_w[k] + contact.row(k).sum();
  }
  if (!deferred) {
    for (Eigen::Index k = 0; k < m; ++k) e.total[alive[k]] += rest[k];
    return e;
  }
  // The last expert where the bound leaves the outcome open. total = (experts' sum + last) + rest, in the order of
  // the undeferred sum; rounding is monotone, so it never exceeds (experts' sum + bound) + rest.
  const Expert& last = *experts.back();
  const double bound = last.max_log_value();
  const Eigen::Index col = e.log_experts.cols() - 1;
  std::vector<Eigen::Index> open;
  for (Eigen::Index k = 0; k < m; ++k) {
    const Eigen::Index i = alive[k];
    if (settled(i, (e.total[i] + bound) + rest[k])) {
      e.total[i] = -std::numeric_limits<double>::infinity();
    } else {
      open.push_back(k);
    }
  }
  if (open.empty()) return e;
  std::vector<Eigen::Index> rows;
  for (const Eigen::Index k : open) rows.push_back(alive[k]);
  const auto [wo, qo] = batch_rows(wrists, joints, rows);
  const Eigen::VectorXd v = last.log_value(GraspBatch{wo, qo});
  if (v.size() != static_cast<Eigen::Index>(rows.size()) || v.array().isNaN().any() || (v.array() > bound).any())
    throw std::invalid_argument("expert '" + last.name() +
                                "' returned NaN, the wrong number of values or more than "
                                "its max_log_value");
  for (size_t j = 0; j < rows.size(); ++j) {
    const Eigen::Index i = rows[j];
    e.log_experts(i, col) = v[static_cast<Eigen::Index>(j)];
    e.total[i] += v[static_cast<Eigen::Index>(j)];
    e.total[i] += rest[open[j]];
  }
  return e;
}

int GraspSynthesizer::anneal(const Scoring& scoring, const AnnealingSettings& s, std::mt19937_64& rng,
                             PoseArray& wrists, RowMatrixXd& joints) const {
  const Eigen::Index n = wrists.rows();
  if (n == 0 || s.iterations <= 0) return 0;
  if (!(s.initial_temperature > 0.0)) throw std::invalid_argument("annealing: initial_temperature must be > 0");
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  const RowMatrixXd& limits = config_.limits();
  const double joint_std = s.joint_step * config_.sigma();
  Eigen::VectorXd current = evaluate(scoring, wrists, joints).total;
  PoseArray best_w = wrists;
  RowMatrixXd best_q = joints;
  Eigen::VectorXd best = current;
  PoseArray prop_w(n, 7);
  RowMatrixXd prop_q(n, joints.cols());
  Eigen::VectorXd draws(n);
  for (int t = 0; t < s.iterations; ++t) {
    // The paper's schedule: linear decay from the initial temperature.
    const double T = s.initial_temperature * (1.0 - static_cast<double>(t) / s.iterations);
    for (Eigen::Index i = 0; i < n; ++i) {
      const Eigen::Vector3d dp(normal(rng), normal(rng), normal(rng));
      const Eigen::Vector3d dr(normal(rng), normal(rng), normal(rng));
      const Eigen::Quaterniond q =
          canonical((quat_row(wrists, i) * quat_exp(0.5 * s.rotation_step * T * dr)).normalized());
      prop_w.row(i).head<3>() = wrists.row(i).head<3>() + s.position_step * T * dp.transpose();
      prop_w.row(i).tail<4>() << q.x(), q.y(), q.z(), q.w();
      for (Eigen::Index j = 0; j < joints.cols(); ++j) {
        prop_q(i, j) = std::clamp(joints(i, j) + joint_std * T * normal(rng), limits(j, 0), limits(j, 1));
      }
    }
    // The acceptance draws, one per chain, as they have always been drawn (after the proposals): a proposal whose
    // log L cannot exceed `bound` is refused when bound < c and u >= exp((bound - c) / T) (with a margin over the
    // rounding of exp), so its last expert (contact quality) need not be scored.
    for (Eigen::Index i = 0; i < n; ++i) draws[i] = uni(rng);
    const auto refused = [&](Eigen::Index i, double bound) {
      const double c = current[i];
      return std::isfinite(c) && bound < c && !(draws[i] < std::exp((bound - c) / T) * (1.0 + 1e-12));
    };
    const Eigen::VectorXd proposed = evaluate_bounded(scoring, prop_w, prop_q, refused).total;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double a = proposed[i], c = current[i];
      const double u = draws[i];
      bool accept;
      if (std::isinf(c) && c < 0) {
        accept = true;  // from a rejected state anything is an improvement or equally bad: keep moving
      } else if (std::isinf(a) && a < 0) {
        accept = false;
      } else {
        accept = a >= c || u < std::exp((a - c) / T);
      }
      if (!accept) continue;
      wrists.row(i) = prop_w.row(i);
      joints.row(i) = prop_q.row(i);
      current[i] = a;
      if (a > best[i]) {
        best[i] = a;
        best_w.row(i) = prop_w.row(i);
        best_q.row(i) = prop_q.row(i);
      }
    }
  }
  wrists = best_w;
  joints = best_q;
  return static_cast<int>(n) * (s.iterations + 1);
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
  for (int round = 0; round < s.sampling.max_sampling_rounds && static_cast<int>(passed.size()) < s.sampling.n_samples;
       ++round) {
    PoseArray w;
    RowMatrixXd q;
    sample_grasps(scoring.query, s.sampling.n_samples, rng, w, q);
    batch_e.push_back(evaluate(scoring, w, q));
    batch_w.push_back(std::move(w));
    batch_q.push_back(std::move(q));
    res.evaluations += s.sampling.n_samples;
    const Evaluation& e = batch_e.back();
    for (Eigen::Index i = 0; i < e.total.size(); ++i) {
      if (e.total[i] > -std::numeric_limits<double>::infinity()) {
        if (static_cast<int>(passed.size()) < s.sampling.n_samples) passed.emplace_back(round, i);
      } else {
        ++res.rejected;
        rejected.emplace_back(round, i);
      }
    }
  }
  // Too few passed: rejected samples fill up (ranked last; still optimised if among the best).
  for (size_t k = 0; static_cast<int>(passed.size()) < s.sampling.n_samples && k < rejected.size(); ++k)
    passed.push_back(rejected[k]);
  Candidates c;
  const Eigen::Index n = static_cast<Eigen::Index>(passed.size());
  c.wrists.resize(n, 7);
  c.joints.resize(n, hand_->n_dofs());
  c.eval = empty_evaluation(n, scoring.query.size(), scoring.experts.size());
  for (Eigen::Index k = 0; k < n; ++k) {
    const auto [b, i] = passed[k];
    c.wrists.row(k) = batch_w[b].row(i);
    c.joints.row(k) = batch_q[b].row(i);
    copy_rows(batch_e[b], {i}, c.eval, {k});
  }
  return c;
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

SynthesisResult GraspSynthesizer::synthesize(const Eigen::Ref<const PoseArray>& frames,
                                             const Eigen::Ref<const RowMatrixXd>& features,
                                             const CollisionExpert& collision,
                                             const std::vector<std::shared_ptr<const Expert>>& experts,
                                             const SynthesizerSettings& s,
                                             const Eigen::Ref<const Eigen::VectorXd>& weights) const {
  if (s.sampling.n_samples < 1) throw std::invalid_argument("synthesize: n_samples must be >= 1");
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
  std::vector<int> order = rank_best_first(c.eval.total);
  res.timing.sampling = seconds_since(t1);

  const auto t2 = std::chrono::steady_clock::now();
  const std::vector<bool> optimised = optimise_best(scoring, s, order, rng, c, res);
  if (s.sampling.optimise) order = rank_best_first(c.eval.total);
  res.timing.optimisation = seconds_since(t2);

  for (const QueryDensity& q : query) res.contact_links.push_back(q.link_name);
  for (const auto& e : experts) res.expert_names.push_back(e->name());
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
