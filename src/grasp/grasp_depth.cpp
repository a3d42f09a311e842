#include "graspmix/grasp/grasp_depth.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "grasp/shape_bounds.hpp"
#include "grasp/wrist_rows.hpp"
#include "graspmix/core/se3.hpp"

namespace graspmix {

namespace {

void check_settings(const GraspDepthSettings& s) {
  for (const auto& [value, what] :
       {std::pair{s.min_depth, "min_depth"}, std::pair{s.penalty, "penalty"}, std::pair{s.min_radius, "min_radius"}}) {
    if (!(std::isfinite(value) && value >= 0.0))
      throw std::invalid_argument(std::string("GraspDepthSettings.") + what + " must be finite and >= 0, got " +
                                  std::to_string(value));
  }
}

}  // namespace

GraspDepthExpert::GraspDepthExpert(std::shared_ptr<const Hand> hand, const Eigen::Ref<const Vec3Array>& points,
                                   GraspDepthSettings settings)
    : hand_(std::move(hand)), settings_(std::move(settings)) {
  if (!hand_) throw std::invalid_argument("GraspDepthExpert: no hand");
  check_settings(settings_);
  if (points.rows() == 0) throw std::invalid_argument("GraspDepthExpert: no points");
  require_finite(points, "GraspDepthExpert: points");
  for (const int l : hand_->fingertips()) {
    std::vector<Eigen::Vector3d> c = shape_corners(hand_->links()[static_cast<size_t>(l)].collisions);
    if (c.empty())
      throw std::invalid_argument("GraspDepthExpert: fingertip link '" + hand_->link_names()[static_cast<size_t>(l)] +
                                  "' of hand '" + hand_->name() + "' has no collision geometry to bound it");
    tips_.push_back(l);
    corners_.push_back(std::move(c));
  }
  if (tips_.empty()) throw std::invalid_argument("GraspDepthExpert: hand '" + hand_->name() + "' has no fingertips");
  // A fixed shuffle: the points of a scan lie all over the object, so one deep enough is met early.
  std::vector<Eigen::Index> order(static_cast<size_t>(points.rows()));
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  std::mt19937 rng(12345u);
  std::shuffle(order.begin(), order.end(), rng);
  points_.resize(points.rows(), 3);
  for (Eigen::Index i = 0; i < points.rows(); ++i) points_.row(i) = points.row(order[static_cast<size_t>(i)]);
}

Eigen::VectorXd GraspDepthExpert::depths(const Eigen::Ref<const PoseArray>& wrists,
                                         const Eigen::Ref<const RowMatrixXd>& joints) const {
  const Eigen::Index n = wrists.rows();
  if (joints.rows() != n || joints.cols() != hand_->n_dofs())
    throw std::invalid_argument("GraspDepthExpert: joints must be (" + std::to_string(n) + ", " +
                                std::to_string(hand_->n_dofs()) + "), got (" + std::to_string(joints.rows()) + ", " +
                                std::to_string(joints.cols()) + ")");
  require_finite(wrists, "GraspDepthExpert: wrists");
  require_finite(joints, "GraspDepthExpert: joints");
  const double need = settings_.min_depth;
  const Eigen::Vector3d axis = hand_->approach_axis().normalized();
  Eigen::VectorXd out(n);
  std::string error;
#pragma omp parallel if (n >= 64)
  {
    std::vector<Eigen::Isometry3d> poses(static_cast<size_t>(hand_->n_links()));
    std::vector<Eigen::Vector3d> middles(tips_.size());
#pragma omp for schedule(dynamic, 16)
    for (Eigen::Index i = 0; i < n; ++i) {
      Eigen::Isometry3d W;
      if (!wrist_of_row(wrists, i, W, error)) continue;
      hand_->fk_into(W, joints.row(i).data(), poses.data());  // a row of a row-major matrix: contiguous
      const Eigen::Vector3d a = W.linear() * axis;
      double reach = -std::numeric_limits<double>::infinity();
      for (size_t f = 0; f < tips_.size(); ++f) {
        middles[f].setZero();
        for (const Eigen::Vector3d& c : corners_[f]) {
          const Eigen::Vector3d w = poses[static_cast<size_t>(tips_[f])] * c;
          reach = std::max(reach, a.dot(w));
          middles[f] += w / static_cast<double>(corners_[f].size());
        }
      }
      const FingertipSpan tips_span = fingertip_span(middles);
      const Eigen::Vector3d& m = tips_span.mean;
      const double half_gap = 0.5 * tips_span.span.norm();
      const double rho2 = std::pow(std::max(half_gap, settings_.min_radius), 2);
      const double tip = reach - a.dot(m);  // the far end's distance along a from the line's point m
      double best = -std::numeric_limits<double>::infinity();
      for (Eigen::Index k = 0; k < points_.rows() && best < need; ++k) {
        const Eigen::Vector3d v = points_.row(k).transpose() - m;
        const double s = a.dot(v);
        if (v.squaredNorm() - s * s < rho2) best = std::max(best, tip - s);
      }
      out[i] = std::isfinite(best) ? std::min(best, need) : 0.0;
    }
  }
  if (!error.empty()) throw std::invalid_argument("GraspDepthExpert: " + error);
  return out;
}

Eigen::VectorXd GraspDepthExpert::log_value(const GraspBatch& batch) const {
  const Eigen::VectorXd d = depths(batch.wrists, batch.joints);
  return -settings_.penalty * (settings_.min_depth - d.array()).max(0.0).matrix();
}

}  // namespace graspmix
