#include "graspmix/grasp/topdown_seeds.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Geometry>

#include "grasp/shape_bounds.hpp"
#include "graspmix/core/se3.hpp"

namespace graspmix {

namespace {

/// Of 36 horizontal directions 5 degrees apart (e1, e2 spanning the table), the one across which the points are
/// narrowest, with the points' extremes along it.
Eigen::Vector3d narrowest(const Vec3Array& points, const Eigen::Vector3d& e1, const Eigen::Vector3d& e2, double& lo,
                          double& hi) {
  Eigen::Vector3d best = e1;
  double width = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 36; ++k) {
    const double a = k * M_PI / 36.0;
    const Eigen::Vector3d d = std::cos(a) * e1 + std::sin(a) * e2;
    const Eigen::VectorXd s = points * d;
    if (s.maxCoeff() - s.minCoeff() < width) {
      width = s.maxCoeff() - s.minCoeff();
      best = d;
      lo = s.minCoeff();
      hi = s.maxCoeff();
    }
  }
  return best;
}

}  // namespace

SeedGrasps topdown_seeds(const Hand& hand, const ConfigModel& config, const Vec3Array& points,
                         const Eigen::Vector4d& plane) {
  SeedGrasps out;
  out.wrists.resize(0, 7);
  out.joints.resize(0, hand.n_dofs());
  const std::vector<int>& tips = hand.fingertips();
  const double norm = plane.head<3>().norm();
  if (points.rows() < 3 || tips.empty() || !(norm > 0.0)) return out;
  const Eigen::Vector3d up = plane.head<3>() / norm;
  const double offset = plane[3] / norm;
  const Eigen::Vector3d e1 = up.unitOrthogonal(), e2 = up.cross(e1);
  // The object: its narrowest horizontal direction n, the centre between its extremes along n and at its centroid
  // across, and its top above the table.
  double lo = 0.0, hi = 0.0;
  const Eigen::Vector3d n = narrowest(points, e1, e2, lo, hi), across = up.cross(n);
  const double top = (points * up).maxCoeff() + offset;
  const Eigen::Vector3d centre = 0.5 * (lo + hi) * n + (points * across).mean() * across - offset * up;
  // The hand at the demonstrated grasp, wrist at the origin: its fingertips' middles, their far end along the
  // approach axis, the closing line.
  const Eigen::Vector3d a = hand.approach_axis().normalized();
  std::vector<Eigen::Vector3d> middles;
  double reach = -std::numeric_limits<double>::infinity();
  for (const LinkBounds& b : link_bounds(hand, tips, config.grasp())) {
    if (b.corners.empty()) continue;
    for (const Eigen::Vector3d& w : b.corners) reach = std::max(reach, a.dot(w));
    middles.push_back(b.middle);
  }
  if (middles.empty()) return out;
  const FingertipSpan tips_span = fingertip_span(middles);
  const Eigen::Vector3d& mean = tips_span.mean;
  Eigen::Vector3d c = middles.size() > 1 ? tips_span.span : a.unitOrthogonal();
  c -= a.dot(c) * a;
  c = c.norm() > 1e-9 ? Eigen::Vector3d(c.normalized()) : Eigen::Vector3d(a.unitOrthogonal());
  const Eigen::Vector3d tip_point = mean - a.dot(mean) * a + reach * a;  // the fingertips' far end, on the axis
  Eigen::Matrix3d hand_axes;
  hand_axes << a, c, a.cross(c);
  std::vector<double> heights;
  for (const double depth : kTopdownSeedDepths) {
    const double h = std::min(top, std::max(top - depth, kTopdownSeedMinHeight));
    if (std::none_of(heights.begin(), heights.end(), [&](double x) { return std::abs(x - h) < 1e-6; }))
      heights.push_back(h);
  }
  // Every configuration of the configuration model's line (its kernels' centres): the object may be wider or
  // narrower than the demonstration's, and the scoring (collision, contact quality) picks the opening.
  const RowMatrixXd& openings = config.kernels();
  out.wrists.resize(static_cast<Eigen::Index>(2 * heights.size()) * openings.rows(), 7);
  out.joints.resize(out.wrists.rows(), hand.n_dofs());
  Eigen::Index row = 0;
  for (const double h : heights) {
    for (const double turn : {1.0, -1.0}) {
      Eigen::Matrix3d world_axes;
      world_axes << -up, turn * n, (-up).cross(turn * n);
      Eigen::Isometry3d W = Eigen::Isometry3d::Identity();
      W.linear() = world_axes * hand_axes.transpose();
      W.translation() = centre + h * up - W.linear() * tip_point;
      for (Eigen::Index k = 0; k < openings.rows(); ++k, ++row) {
        out.wrists.row(row) = pose_to_vector(W).transpose();
        out.joints.row(row) = openings.row(k);
      }
    }
  }
  return out;
}

}  // namespace graspmix
