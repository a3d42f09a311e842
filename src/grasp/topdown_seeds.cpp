#include "graspmix/grasp/topdown_seeds.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Geometry>

#include "grasp/object_parts.hpp"
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

/// The free gap between fingertips (their shape bounds, at least one): along the line from the first fingertip's
/// middle to the mean of the others', from the first's farthest point along it to the nearest point of the others;
/// 0 for one fingertip.
double inner_gap(const std::vector<LinkBounds>& tips) {
  std::vector<Eigen::Vector3d> middles;
  for (const LinkBounds& b : tips) middles.push_back(b.middle);
  const Eigen::Vector3d span = fingertip_span(middles).span;
  if (tips.size() < 2 || !(span.norm() > 0.0)) return 0.0;
  const Eigen::Vector3d c = span.normalized();
  double first = -std::numeric_limits<double>::infinity(), others = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& w : tips.front().corners) first = std::max(first, c.dot(w));
  for (std::size_t f = 1; f < tips.size(); ++f)
    for (const Eigen::Vector3d& w : tips[f].corners) others = std::min(others, c.dot(w));
  return std::max(0.0, others - first);
}

/// The bounds (link_bounds) of those of `links` that have collision shapes, at q.
std::vector<LinkBounds> shaped_bounds(const Hand& hand, const std::vector<int>& links, const Eigen::VectorXd& q) {
  std::vector<LinkBounds> out = link_bounds(hand, links, q);
  out.erase(std::remove_if(out.begin(), out.end(), [](const LinkBounds& b) { return b.corners.empty(); }), out.end());
  return out;
}

/// The hand at the demonstrated grasp, wrist at the origin: its axes (approach a, closing c, a x c as columns) and
/// its fingertips' far end on the approach axis; per configuration of the model's line the free gap between the
/// fingertips (inner_gap); half the first fingertip's width across the closing line. False for a hand whose
/// fingertips have no shapes or a model without configurations.
struct HandAtGrasp {
  Eigen::Matrix3d axes;
  Eigen::Vector3d tip_point;
  std::vector<double> gaps;
  double half_width = 0.0;  ///< half the first fingertip (with shapes)'s extent across the closing line (a x c)
};

bool hand_at_grasp(const Hand& hand, const ConfigModel& config, HandAtGrasp& out) {
  const std::vector<int>& tips = hand.fingertips();
  const Eigen::Vector3d a = hand.approach_axis().normalized();
  std::vector<Eigen::Vector3d> middles;
  double reach = -std::numeric_limits<double>::infinity();
  const std::vector<LinkBounds> at_grasp = shaped_bounds(hand, tips, config.grasp());
  for (const LinkBounds& b : at_grasp) {
    for (const Eigen::Vector3d& w : b.corners) reach = std::max(reach, a.dot(w));
    middles.push_back(b.middle);
  }
  if (middles.empty() || config.kernels().rows() == 0) return false;
  const FingertipSpan tips_span = fingertip_span(middles);
  const Eigen::Vector3d& mean = tips_span.mean;
  Eigen::Vector3d c = middles.size() > 1 ? tips_span.span : a.unitOrthogonal();
  c -= a.dot(c) * a;
  c = c.norm() > 1e-9 ? Eigen::Vector3d(c.normalized()) : Eigen::Vector3d(a.unitOrthogonal());
  out.tip_point = mean - a.dot(mean) * a + reach * a;
  out.axes << a, c, a.cross(c);
  double wlo = std::numeric_limits<double>::infinity(), whi = -wlo;
  for (const Eigen::Vector3d& w : at_grasp.front().corners) {
    wlo = std::min(wlo, a.cross(c).dot(w));
    whi = std::max(whi, a.cross(c).dot(w));
  }
  out.half_width = 0.5 * (whi - wlo);
  const RowMatrixXd& openings = config.kernels();
  out.gaps.clear();
  for (Eigen::Index k = 0; k < openings.rows(); ++k) {
    out.gaps.push_back(inner_gap(shaped_bounds(hand, tips, openings.row(k).transpose())));
  }
  return true;
}

/// The heights above the table of the fingertips' far end: kTopdownSeedDepths below `top`, never lower than
/// kTopdownSeedMinHeight, each once.
std::vector<double> seed_heights(double top) {
  std::vector<double> heights;
  for (const double depth : kTopdownSeedDepths) {
    const double h = std::min(top, std::max(top - depth, kTopdownSeedMinHeight));
    if (std::none_of(heights.begin(), heights.end(), [&](double x) { return std::abs(x - h) < 1e-6; }))
      heights.push_back(h);
  }
  return heights;
}

/// Appends the seeds over `centre` (on the table): closing along n, at each of the heights below `top` and turned
/// both ways about the approach, at the configurations `rows` of the model's line.
void add_seeds(SeedGrasps& out, const HandAtGrasp& h, const RowMatrixXd& openings,
               const std::vector<Eigen::Index>& rows, const Eigen::Vector3d& up, const Eigen::Vector3d& n,
               const Eigen::Vector3d& centre, double top) {
  const std::vector<double> heights = seed_heights(top);
  Eigen::Index row = out.wrists.rows();
  out.wrists.conservativeResize(row + static_cast<Eigen::Index>(2 * heights.size() * rows.size()), 7);
  out.joints.conservativeResize(out.wrists.rows(), openings.cols());
  for (const double height : heights) {
    for (const double turn : {1.0, -1.0}) {
      Eigen::Matrix3d world_axes;
      world_axes << -up, turn * n, (-up).cross(turn * n);
      Eigen::Isometry3d W = Eigen::Isometry3d::Identity();
      W.linear() = world_axes * h.axes.transpose();
      W.translation() = centre + height * up - W.linear() * h.tip_point;
      for (const Eigen::Index k : rows) {
        out.wrists.row(row) = pose_to_vector(W).transpose();
        out.joints.row(row++) = openings.row(k);
      }
    }
  }
}

/// The part seeds (graspable_parts) of an object wider than the hand opens: each over its middle along its
/// direction, under its own top, at the configurations whose gap is at least its width and at most kPartSeedSlack
/// more (the narrowest wider one if none).
void add_part_seeds(SeedGrasps& out, const HandAtGrasp& h, const RowMatrixXd& openings, const Vec3Array& points,
                    const Vec3Array& others, const Eigen::Vector3d& up, double offset, double widest) {
  for (const ObjectPart& part : graspable_parts(points, others, up, offset, h.half_width, widest)) {
    std::vector<Eigen::Index> rows;
    Eigen::Index narrowest_wider = -1;
    for (Eigen::Index k = 0; k < openings.rows(); ++k) {
      const double g = h.gaps[static_cast<std::size_t>(k)];
      if (g >= part.width && g <= part.width + kPartSeedSlack) rows.push_back(k);
      if (g >= part.width && (narrowest_wider < 0 || g < h.gaps[static_cast<std::size_t>(narrowest_wider)]))
        narrowest_wider = k;
    }
    if (rows.empty() && narrowest_wider >= 0) rows.push_back(narrowest_wider);
    if (!rows.empty()) add_seeds(out, h, openings, rows, up, part.direction, part.middle, part.top);
  }
}

}  // namespace

SeedGrasps topdown_seeds(const Hand& hand, const ConfigModel& config, const Vec3Array& points,
                         const Eigen::Vector4d& plane, const Vec3Array& others) {
  SeedGrasps out;
  out.wrists.resize(0, 7);
  out.joints.resize(0, hand.n_dofs());
  const double norm = plane.head<3>().norm();
  HandAtGrasp h;
  if (points.rows() < 3 || !points.allFinite() || hand.fingertips().empty() || !(norm > 0.0) ||
      !hand_at_grasp(hand, config, h))
    return out;
  const Eigen::Vector3d up = plane.head<3>() / norm;
  const double offset = plane[3] / norm;
  const Eigen::Vector3d e1 = up.unitOrthogonal(), e2 = up.cross(e1);
  // The object: its narrowest horizontal direction n, the centre between its extremes along n and at its centroid
  // across, and its top above the table.
  double lo = 0.0, hi = 0.0;
  const Eigen::Vector3d n = narrowest(points, e1, e2, lo, hi), across = up.cross(n);
  const double top = (points * up).maxCoeff() + offset;
  const Eigen::Vector3d centre = 0.5 * (lo + hi) * n + (points * across).mean() * across - offset * up;
  // Every configuration of the configuration model's line (its kernels' centres): the object may be wider or
  // narrower than the demonstration's, and the scoring (collision, contact quality) picks the opening.
  const RowMatrixXd& openings = config.kernels();
  std::vector<Eigen::Index> all(static_cast<std::size_t>(openings.rows()));
  for (Eigen::Index k = 0; k < openings.rows(); ++k) all[static_cast<std::size_t>(k)] = k;
  add_seeds(out, h, openings, all, up, n, centre, top);
  // An object wider than the hand's widest gap: its parts too (a hand with one fingertip has no gap).
  const double widest = *std::max_element(h.gaps.begin(), h.gaps.end());
  if (widest > kPartSeedCell && hi - lo > widest) add_part_seeds(out, h, openings, points, others, up, offset, widest);
  return out;
}

}  // namespace graspmix
