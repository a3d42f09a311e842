// GraspSynthesizer's scoring of grasps by the product of experts (eq:opt_criterion_extended) and the simulated
// annealing that climbs it; the sampling and the whole synthesis are in synthesis.cpp.
#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include <omp.h>

#include "graspmix/core/se3.hpp"
#include "graspmix/grasp/synthesis.hpp"

namespace graspmix {

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
    if (query[l].floor)
      contact.col(l) = contact.col(l).unaryExpr([&](double v) { return contact_log_term(v, query[l].floor); });
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
    // The links' terms added in link order: Eigen's vectorised row sum starts at the first aligned element, so its
    // order (and last bit) would depend on the grasp's row in the batch, and the batch on the other grasps in it.
    double links = 0;
    for (Eigen::Index l = 0; l < contact.cols(); ++l) links += contact(k, l);
    rest[k] = coll[k] + config[k] + pre_w[k] + links;
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

/// The random numbers of an annealing run, drawn before any chain moves, in the order the chains have always
/// drawn them: per iteration, each chain's proposal (3 position, 3 rotation, then one per joint normal deviates),
/// then each chain's acceptance number. None depends on a score, so chains drawn this way can run apart.
struct GraspSynthesizer::AnnealingNoise {
  std::vector<RowMatrixXd> steps;      ///< per iteration (n, 6 + D)
  std::vector<Eigen::VectorXd> draws;  ///< per iteration (n), uniform in [0, 1)

  AnnealingNoise(std::mt19937_64& rng, Eigen::Index n, Eigen::Index dofs, int iterations) {
    std::normal_distribution<double> normal;
    std::uniform_real_distribution<double> uni(0.0, 1.0);
    steps.reserve(static_cast<size_t>(iterations));
    draws.reserve(static_cast<size_t>(iterations));
    for (int t = 0; t < iterations; ++t) {
      RowMatrixXd step(n, 6 + dofs);
      for (Eigen::Index i = 0; i < n; ++i)
        for (Eigen::Index j = 0; j < step.cols(); ++j) step(i, j) = normal(rng);
      Eigen::VectorXd u(n);
      for (Eigen::Index i = 0; i < n; ++i) u[i] = uni(rng);
      steps.push_back(std::move(step));
      draws.push_back(std::move(u));
    }
  }
};

namespace {

/// Chains per thread below which annealing stays on one thread: a chain's iteration costs tens of microseconds,
/// a team's wake-up about as much.
constexpr Eigen::Index kChainsPerThread = 4;

}  // namespace

void GraspSynthesizer::anneal_chains(const Scoring& scoring, const AnnealingSettings& s, const AnnealingNoise& noise,
                                     Eigen::Index first, PoseArray& wrists, RowMatrixXd& joints) const {
  const Eigen::Index n = wrists.rows(), D = joints.cols();
  const RowMatrixXd& limits = config_.limits();
  const double joint_std = s.joint_step * config_.sigma();
  Eigen::VectorXd current = evaluate(scoring, wrists, joints).total;
  PoseArray best_w = wrists;
  RowMatrixXd best_q = joints;
  Eigen::VectorXd best = current;
  PoseArray prop_w(n, 7);
  RowMatrixXd prop_q(n, D);
  for (int t = 0; t < s.iterations; ++t) {
    // The paper's schedule: linear decay from the initial temperature.
    const double T = s.initial_temperature * (1.0 - static_cast<double>(t) / s.iterations);
    const auto step = noise.steps[static_cast<size_t>(t)].middleRows(first, n);
    const auto draws = noise.draws[static_cast<size_t>(t)].segment(first, n);
    for (Eigen::Index i = 0; i < n; ++i) {
      // Each triple's deviates taken last first: the order GCC evaluated the arguments of the Vector3d(normal(rng),
      // ...) this code replaced, so the grasps of every run recorded in docs stay what they were.
      const Eigen::Vector3d dp = step.row(i).head<3>().reverse().transpose();
      const Eigen::Vector3d dr = step.row(i).segment<3>(3).reverse().transpose();
      const Eigen::Quaterniond q =
          canonical((row_quaternion(wrists, i).normalized() * quat_exp(0.5 * s.rotation_step * T * dr)).normalized());
      prop_w.row(i).head<3>() = wrists.row(i).head<3>() + s.position_step * T * dp.transpose();
      prop_w.row(i).tail<4>() << q.x(), q.y(), q.z(), q.w();
      for (Eigen::Index j = 0; j < D; ++j) {
        prop_q(i, j) = std::clamp(joints(i, j) + joint_std * T * step(i, 6 + j), limits(j, 0), limits(j, 1));
      }
    }
    // A proposal whose log L cannot exceed `bound` is refused when bound < c and u >= exp((bound - c) / T) (with a
    // margin over the rounding of exp), so its last expert (contact quality) need not be scored.
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
}

int GraspSynthesizer::anneal(const Scoring& scoring, const AnnealingSettings& s, std::mt19937_64& rng,
                             PoseArray& wrists, RowMatrixXd& joints) const {
  const Eigen::Index n = wrists.rows();
  if (n == 0 || s.iterations <= 0) return 0;
  if (!(s.initial_temperature > 0.0)) throw std::invalid_argument("annealing: initial_temperature must be > 0");
  require_joints_shape(n, joints, hand_->n_dofs(), "anneal");  // before the rows are split into blocks
  const AnnealingNoise noise(rng, n, joints.cols(), s.iterations);
  // Chains share nothing but their noise: blocks of them anneal on threads of their own, each grasp scored as in
  // one batch (the experts allowing it), so the result is the same whatever the threads.
  const bool in_parts =
      std::all_of(scoring.experts.begin(), scoring.experts.end(), [](const auto& e) { return e->scores_in_parts(); });
  const int threads =
      in_parts ? static_cast<int>(std::min<Eigen::Index>(omp_get_max_threads(), n / kChainsPerThread)) : 1;
  if (threads <= 1) {
    anneal_chains(scoring, s, noise, 0, wrists, joints);
    return static_cast<int>(n) * (s.iterations + 1);
  }
  std::vector<std::exception_ptr> errors(static_cast<size_t>(threads));
#pragma omp parallel num_threads(threads)
  {
    const int k = omp_get_thread_num(), team = omp_get_num_threads();
    const Eigen::Index first = n * k / team, count = n * (k + 1) / team - first;
    try {
      PoseArray w = wrists.middleRows(first, count);
      RowMatrixXd q = joints.middleRows(first, count);
      anneal_chains(scoring, s, noise, first, w, q);
      wrists.middleRows(first, count) = w;
      joints.middleRows(first, count) = q;
    } catch (...) {
      errors[static_cast<size_t>(k)] = std::current_exception();
    }
  }
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
  return static_cast<int>(n) * (s.iterations + 1);
}

}  // namespace graspmix
