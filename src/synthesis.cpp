#include "graspmix/synthesis.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include "graspmix/pose_mixture.hpp"
#include "graspmix/se3.hpp"

namespace graspmix {

namespace {

constexpr double kPi = 3.14159265358979323846;

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

}  // namespace

GraspSynthesizer::GraspSynthesizer(std::shared_ptr<const Hand> hand, std::vector<ContactModel> contact_models,
                                   ConfigModel config)
    : hand_(std::move(hand)), contact_models_(std::move(contact_models)), config_(std::move(config)) {
  if (!hand_) throw std::invalid_argument("GraspSynthesizer: no hand");
  if (contact_models_.empty()) throw std::invalid_argument("GraspSynthesizer: no contact models");
  if (config_.dim() != hand_->n_dofs()) {
    throw std::invalid_argument("GraspSynthesizer: the configuration model has " + std::to_string(config_.dim()) +
                                " joints, the hand '" + hand_->name() + "' has " + std::to_string(hand_->n_dofs()));
  }
  const std::string kind = contact_models_.front().density ? contact_models_.front().density->kind() : "";
  for (const ContactModel& m : contact_models_) {
    if (!m.density || !m.density->fitted()) throw std::invalid_argument("GraspSynthesizer: contact model of link '" + m.link_name + "' is not fitted");
    if (m.link < 0 || m.link >= hand_->n_links() || hand_->link_names()[m.link] != m.link_name) {
      throw std::invalid_argument("GraspSynthesizer: contact model link '" + m.link_name + "' is not link " +
                                  std::to_string(m.link) + " of hand '" + hand_->name() + "'");
    }
    if (m.density->kind() != kind) throw std::invalid_argument("GraspSynthesizer: contact models mix GMM and KDE densities");
  }
}

std::string GraspSynthesizer::method() const { return contact_models_.front().density->kind(); }

std::vector<QueryDensity> GraspSynthesizer::query_densities(const Eigen::Ref<const PoseArray>& frames,
                                                            const Eigen::Ref<const RowMatrixXd>& features,
                                                            const QuerySettings& s, std::mt19937_64& rng) const {
  if (frames.rows() == 0) throw std::invalid_argument("query densities: the object has no surface points");
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
  std::vector<QueryDensity> out;
  for (const ContactModel& m : contact_models_) {
    // Importance resampling: surface points in proportion to M_i(r).
    auto pick = distribution_from_logs(m.density->feature_log_density(features));
    PoseArray v(s.n_samples, 7);
    RowMatrixXd r(s.n_samples, features.cols());
    for (int k = 0; k < s.n_samples; ++k) {
      const int j = pick(rng);
      v.row(k) = frames.row(j);
      r.row(k) = features.row(j);
      if (s.frame_jitter && features.cols() >= 2) {
        const double k1 = features(j, 0), k2 = features(j, 1);
        const double rel = k1 > 1e-12 ? (k1 - k2) / k1 : 0.0;
        const double angle = uni(rng) * kPi * std::exp(-s.jitter_sharpness * rel * rel);
        const Eigen::Quaterniond q = quat_row(v, k) * Eigen::Quaterniond(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()));
        v.row(k).tail<4>() << q.x(), q.y(), q.z(), q.w();
      }
    }
    const PoseArray u = m.density->sample(r, rng);
    const PoseArray samples = pose_multiply(v, u);  // s = v o u
    std::shared_ptr<PoseDensity> q;
    if (m.density->kind() == "gmm") {
      GmmSettings g;
      g.n_components = s.n_components;
      g.max_iter = s.max_iter;
      g.reg_covar = s.reg_covar;
      g.seed = rng();
      q = std::make_shared<PoseMixture>(g);
    } else {
      q = std::make_shared<PoseKDE>(s.kde);
    }
    q->fit(samples, RowMatrixXd(s.n_samples, 0), {});
    out.push_back({m.link, m.link_name, std::move(q)});
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

Evaluation GraspSynthesizer::evaluate(const std::vector<QueryDensity>& query, const CollisionExpert& collision,
                                      const std::vector<std::shared_ptr<const Expert>>& experts,
                                      const Eigen::Ref<const PoseArray>& wrists_in,
                                      const Eigen::Ref<const RowMatrixXd>& joints_in, bool clear_pregrasp) const {
  const Eigen::Index n = wrists_in.rows();
  if (joints_in.rows() != n || joints_in.cols() != hand_->n_dofs()) {
    throw std::invalid_argument("evaluate: joints must be (" + std::to_string(n) + ", " +
                                std::to_string(hand_->n_dofs()) + ")");
  }
  const PoseArray wrists = wrists_in;
  const RowMatrixXd joints = joints_in;
  Evaluation e;
  // The experts first: a grasp a hard expert rejects costs nothing more (its other terms stay NaN,
  // "not evaluated"), which keeps rejection sampling cheap.
  e.log_experts.resize(n, experts.size());
  const GraspBatch batch{wrists, joints};
  for (size_t k = 0; k < experts.size(); ++k) e.log_experts.col(k) = experts[k]->log_value(batch);
  e.total = e.log_experts.rowwise().sum();
  std::vector<Eigen::Index> alive;
  for (Eigen::Index i = 0; i < n; ++i)
    if (e.total[i] > -std::numeric_limits<double>::infinity()) alive.push_back(i);
  const Eigen::Index m = static_cast<Eigen::Index>(alive.size());
  PoseArray w(m, 7);
  RowMatrixXd q(m, joints.cols());
  for (Eigen::Index k = 0; k < m; ++k) {
    w.row(k) = wrists.row(alive[k]);
    q.row(k) = joints.row(alive[k]);
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  e.log_contact = RowMatrixXd::Constant(n, query.size(), nan);
  e.log_config = e.log_collision = e.log_pregrasp = Eigen::VectorXd::Constant(n, nan);
  if (m > 0) {
    const RowMatrixXd link_poses = hand_->fk_batch(w, q);
    RowMatrixXd contact(m, query.size());
    for (size_t l = 0; l < query.size(); ++l) {
      const PoseArray P = link_poses.middleCols(7 * query[l].link, 7);
      contact.col(l) = query[l].density->log_density(P, RowMatrixXd(m, 0));
    }
    const Eigen::VectorXd config = config_.log_density(q);
    const Eigen::VectorXd coll = collision.evaluate_batch(w, q).log_w;
    Eigen::VectorXd pre_w = Eigen::VectorXd::Zero(m);
    if (clear_pregrasp) {
      RowMatrixXd pre(m, q.cols());
      for (Eigen::Index k = 0; k < m; ++k) pre.row(k) = config_.pregrasp_for(q.row(k).transpose()).transpose();
      pre_w = collision.evaluate_batch(w, pre).log_w;
    }
    for (Eigen::Index k = 0; k < m; ++k) {
      const Eigen::Index i = alive[k];
      e.log_contact.row(i) = contact.row(k);
      e.log_config[i] = config[k];
      e.log_collision[i] = coll[k];
      e.log_pregrasp[i] = pre_w[k];
      e.total[i] += coll[k] + config[k] + pre_w[k] + contact.row(k).sum();
    }
  }
  return e;
}

int GraspSynthesizer::anneal(const std::vector<QueryDensity>& query, const CollisionExpert& collision,
                             const std::vector<std::shared_ptr<const Expert>>& experts, const AnnealingSettings& s,
                             std::mt19937_64& rng, PoseArray& wrists, RowMatrixXd& joints, bool clear_pregrasp) const {
  const Eigen::Index n = wrists.rows();
  if (n == 0 || s.iterations <= 0) return 0;
  if (!(s.initial_temperature > 0.0)) throw std::invalid_argument("annealing: initial_temperature must be > 0");
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  const RowMatrixXd& limits = config_.limits();
  const double joint_std = s.joint_step * config_.sigma();
  Eigen::VectorXd current = evaluate(query, collision, experts, wrists, joints, clear_pregrasp).total;
  PoseArray best_w = wrists;
  RowMatrixXd best_q = joints;
  Eigen::VectorXd best = current;
  PoseArray prop_w(n, 7);
  RowMatrixXd prop_q(n, joints.cols());
  for (int t = 0; t < s.iterations; ++t) {
    // The paper's schedule: linear decay from the initial temperature.
    const double T = s.initial_temperature * (1.0 - static_cast<double>(t) / s.iterations);
    for (Eigen::Index i = 0; i < n; ++i) {
      const Eigen::Vector3d dp(normal(rng), normal(rng), normal(rng));
      const Eigen::Vector3d dr(normal(rng), normal(rng), normal(rng));
      const Eigen::Quaterniond q = quat_row(wrists, i) * quat_exp(0.5 * s.rotation_step * T * dr);
      prop_w.row(i).head<3>() = wrists.row(i).head<3>() + s.position_step * T * dp.transpose();
      prop_w.row(i).tail<4>() << q.x(), q.y(), q.z(), q.w();
      for (Eigen::Index j = 0; j < joints.cols(); ++j) {
        prop_q(i, j) = std::clamp(joints(i, j) + joint_std * T * normal(rng), limits(j, 0), limits(j, 1));
      }
    }
    const Eigen::VectorXd proposed = evaluate(query, collision, experts, prop_w, prop_q, clear_pregrasp).total;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double a = proposed[i], c = current[i];
      const double u = uni(rng);
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

SynthesisResult GraspSynthesizer::synthesize(const Eigen::Ref<const PoseArray>& frames,
                                             const Eigen::Ref<const RowMatrixXd>& features,
                                             const CollisionExpert& collision,
                                             const std::vector<std::shared_ptr<const Expert>>& experts,
                                             const SynthesisSettings& s) const {
  if (s.n_samples < 1) throw std::invalid_argument("synthesize: n_samples must be >= 1");
  if (s.n_optimise < 0) throw std::invalid_argument("synthesize: n_optimise must be >= 0");
  if (&collision.hand() != hand_.get() && collision.hand().name() != hand_->name()) {
    throw std::invalid_argument("synthesize: the collision expert was built for hand '" + collision.hand().name() +
                                "', the model for '" + hand_->name() + "'");
  }
  const auto t0 = std::chrono::steady_clock::now();
  std::mt19937_64 rng(s.seed);
  SynthesisResult res;
  const std::vector<QueryDensity> query = query_densities(frames, features, s.query, rng);
  res.timing.query = seconds_since(t0);

  const auto t1 = std::chrono::steady_clock::now();
  // Rejection sampling: draw batches until n_samples grasps pass the hard constraints (finite log L).
  PoseArray wrists(0, 7);
  RowMatrixXd joints(0, hand_->n_dofs());
  PoseArray rejected_w(0, 7);
  RowMatrixXd rejected_q(0, hand_->n_dofs());
  for (int round = 0; round < std::max(1, s.max_sampling_rounds) && wrists.rows() < s.n_samples; ++round) {
    PoseArray w;
    RowMatrixXd q;
    sample_grasps(query, s.n_samples, rng, w, q);
    const Evaluation e = evaluate(query, collision, experts, w, q, s.clear_pregrasp);
    res.evaluations += s.n_samples;
    for (Eigen::Index i = 0; i < w.rows(); ++i) {
      const bool ok = std::isfinite(e.total[i]);
      PoseArray& W = ok ? wrists : rejected_w;
      RowMatrixXd& Q = ok ? joints : rejected_q;
      if (ok && W.rows() >= s.n_samples) continue;
      if (!ok) ++res.rejected;
      W.conservativeResize(W.rows() + 1, 7);
      W.row(W.rows() - 1) = w.row(i);
      Q.conservativeResize(Q.rows() + 1, Eigen::NoChange);
      Q.row(Q.rows() - 1) = q.row(i);
    }
  }
  // Too few passed: fill up with rejected samples (ranked last, still optimised if among the best).
  for (Eigen::Index i = 0; wrists.rows() < s.n_samples && i < rejected_w.rows(); ++i) {
    wrists.conservativeResize(wrists.rows() + 1, 7);
    wrists.row(wrists.rows() - 1) = rejected_w.row(i);
    joints.conservativeResize(joints.rows() + 1, Eigen::NoChange);
    joints.row(joints.rows() - 1) = rejected_q.row(i);
  }
  Evaluation ev = evaluate(query, collision, experts, wrists, joints, s.clear_pregrasp);
  auto ranking = [](const Eigen::VectorXd& total) {
    std::vector<int> order(total.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return total[a] > total[b]; });
    return order;
  };
  std::vector<int> order = ranking(ev.total);
  res.timing.sampling = seconds_since(t1);

  const auto t2 = std::chrono::steady_clock::now();
  std::vector<bool> optimised(s.n_samples, false);
  const int n_opt = s.optimise ? std::min(s.n_optimise, s.n_samples) : 0;
  if (n_opt > 0) {
    PoseArray w(n_opt, 7);
    RowMatrixXd q(n_opt, joints.cols());
    for (int k = 0; k < n_opt; ++k) {
      w.row(k) = wrists.row(order[k]);
      q.row(k) = joints.row(order[k]);
    }
    res.evaluations += anneal(query, collision, experts, s.annealing, rng, w, q, s.clear_pregrasp);
    for (int k = 0; k < n_opt; ++k) {
      wrists.row(order[k]) = w.row(k);
      joints.row(order[k]) = q.row(k);
      optimised[order[k]] = true;
    }
    ev = evaluate(query, collision, experts, wrists, joints, s.clear_pregrasp);
    order = ranking(ev.total);
  }
  res.timing.optimisation = seconds_since(t2);

  for (const QueryDensity& q : query) res.contact_links.push_back(q.link_name);
  for (const auto& e : experts) res.expert_names.push_back(e->name());
  res.grasps.reserve(s.n_samples);
  for (int i : order) {
    Grasp g;
    g.T_world_wrist = wrists.row(i).transpose();
    g.joints = joints.row(i).transpose();
    g.pregrasp = config_.pregrasp_for(g.joints);
    g.log_likelihood = ev.total[i];
    g.log_collision = ev.log_collision[i];
    g.log_config = ev.log_config[i];
    g.log_pregrasp = ev.log_pregrasp[i];
    g.log_contact = ev.log_contact.row(i).transpose();
    g.log_experts = ev.log_experts.row(i).transpose();
    g.optimised = optimised[i];
    res.grasps.push_back(std::move(g));
  }
  res.timing.total = seconds_since(t0);
  return res;
}

}  // namespace graspmix
