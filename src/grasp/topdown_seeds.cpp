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

/// The hand at the demonstrated grasp, wrist at the origin: its axes (approach a, closing c, a x c as columns) and
/// its fingertips' far end on the approach axis; per configuration of the model's line the free gap between the
/// fingertips (inner_gap); half the first fingertip's width across the closing line. False for a hand whose
/// fingertips have no shapes.
struct HandAtGrasp {
  Eigen::Matrix3d axes;
  Eigen::Vector3d tip_point;
  std::vector<double> gaps;
  double half_width = 0.0;  ///< half the first fingertip's extent across the closing line (a x c)
};

bool hand_at_grasp(const Hand& hand, const ConfigModel& config, HandAtGrasp& out) {
  const std::vector<int>& tips = hand.fingertips();
  const Eigen::Vector3d a = hand.approach_axis().normalized();
  std::vector<Eigen::Vector3d> middles;
  double reach = -std::numeric_limits<double>::infinity();
  for (const LinkBounds& b : link_bounds(hand, tips, config.grasp())) {
    if (b.corners.empty()) continue;
    for (const Eigen::Vector3d& w : b.corners) reach = std::max(reach, a.dot(w));
    middles.push_back(b.middle);
  }
  if (middles.empty()) return false;
  const FingertipSpan tips_span = fingertip_span(middles);
  const Eigen::Vector3d& mean = tips_span.mean;
  Eigen::Vector3d c = middles.size() > 1 ? tips_span.span : a.unitOrthogonal();
  c -= a.dot(c) * a;
  c = c.norm() > 1e-9 ? Eigen::Vector3d(c.normalized()) : Eigen::Vector3d(a.unitOrthogonal());
  out.tip_point = mean - a.dot(mean) * a + reach * a;
  out.axes << a, c, a.cross(c);
  double wlo = std::numeric_limits<double>::infinity(), whi = -wlo;
  const std::vector<LinkBounds> first = link_bounds(hand, {tips.front()}, config.grasp());
  for (const Eigen::Vector3d& w : first.front().corners) {
    wlo = std::min(wlo, a.cross(c).dot(w));
    whi = std::max(whi, a.cross(c).dot(w));
  }
  out.half_width = std::isfinite(whi - wlo) ? 0.5 * (whi - wlo) : 0.0;
  const RowMatrixXd& openings = config.kernels();
  out.gaps.clear();
  for (Eigen::Index k = 0; k < openings.rows(); ++k) {
    std::vector<LinkBounds> bounds = link_bounds(hand, tips, openings.row(k).transpose());
    bounds.erase(std::remove_if(bounds.begin(), bounds.end(), [](const LinkBounds& b) { return b.corners.empty(); }),
                 bounds.end());
    out.gaps.push_back(inner_gap(bounds));
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

/// The object's footprint on the table in cells of kPartSeedCell: which cells hold a point, and the highest point
/// above each.
struct Footprint {
  double u0 = 0.0, v0 = 0.0;
  int nu = 0, nv = 0;
  std::vector<double> top;  ///< per cell (u fastest), -inf where no point
  bool occupied(double u, double v) const {
    const double i = std::floor((u - u0) / kPartSeedCell), j = std::floor((v - v0) / kPartSeedCell);
    return i >= 0 && j >= 0 && i < nu && j < nv &&
           top[static_cast<std::size_t>(j * nu + i)] > -std::numeric_limits<double>::infinity();
  }
  double height(double u, double v) const {
    const int i = static_cast<int>(std::floor((u - u0) / kPartSeedCell)),
              j = static_cast<int>(std::floor((v - v0) / kPartSeedCell));
    return top[static_cast<std::size_t>(j * nu + i)];
  }
};

Footprint footprint(const Eigen::VectorXd& u, const Eigen::VectorXd& v, const Eigen::VectorXd& z) {
  Footprint f;
  f.u0 = u.minCoeff();
  f.v0 = v.minCoeff();
  f.nu = static_cast<int>(std::floor((u.maxCoeff() - f.u0) / kPartSeedCell)) + 1;
  f.nv = static_cast<int>(std::floor((v.maxCoeff() - f.v0) / kPartSeedCell)) + 1;
  f.top.assign(static_cast<std::size_t>(f.nu) * static_cast<std::size_t>(f.nv),
               -std::numeric_limits<double>::infinity());
  for (Eigen::Index i = 0; i < u.size(); ++i) {
    const int a = std::min(f.nu - 1, static_cast<int>(std::floor((u[i] - f.u0) / kPartSeedCell)));
    const int b = std::min(f.nv - 1, static_cast<int>(std::floor((v[i] - f.v0) / kPartSeedCell)));
    double& t = f.top[static_cast<std::size_t>(b * f.nu + a)];
    t = std::max(t, z[i]);
  }
  return f;
}

/// A part of the footprint through (u, v) along the unit direction (du, dv): from the point, outwards both ways,
/// cell by cell until two cells in a row hold no point; its ends (along the direction, each half a cell beyond the
/// last occupied cell; lo = hi = 0 from a cell that holds no point) and the highest point on the way (-inf: none).
void chord(const Footprint& f, double u, double v, double du, double dv, double& lo, double& hi, double& top) {
  lo = hi = 0.0;
  top = -std::numeric_limits<double>::infinity();
  if (!f.occupied(u, v)) return;
  top = f.height(u, v);
  for (const double sign : {-1.0, 1.0}) {
    double last = 0.0;
    for (int step = 1, empty = 0; empty < 2; ++step) {
      const double t = sign * step * kPartSeedCell, x = u + t * du, y = v + t * dv;
      if (!f.occupied(x, y)) {
        ++empty;
        continue;
      }
      empty = 0;
      last = t;
      top = std::max(top, f.height(x, y));
    }
    (sign < 0 ? lo : hi) = last + sign * 0.5 * kPartSeedCell;
  }
}

/// A part the fingers can close across: its middle (u, v) on the table, the direction of the closing line, the
/// width along it (the union of the three chords) and the highest point under the fingers.
struct Part {
  Eigen::Vector2d middle;
  double angle = 0.0, width = 0.0, top = 0.0;
};

/// The parts of the footprint with parallel walls: along each of 18 directions 10 degrees apart, every chord (chord)
/// of the lines across the footprint one cell apart, taken where the chords half_width to either side across (the
/// fingers' sides), where they start in the footprint, end within kPartSeedTaper of its ends; the width is their
/// union's.
std::vector<Part> parallel_parts(const Footprint& f, const std::vector<Eigen::Vector2d>& cells, double half_width) {
  std::vector<Part> out;
  for (int k = 0; k < 18; ++k) {
    const double a = k * M_PI / 18.0;
    const Eigen::Vector2d d(std::cos(a), std::sin(a)), e(-d.y(), d.x());
    double tmin = std::numeric_limits<double>::infinity(), tmax = -tmin, smin = tmin, smax = -tmin;
    for (const Eigen::Vector2d& c : cells) {
      tmin = std::min(tmin, c.dot(d));
      tmax = std::max(tmax, c.dot(d));
      smin = std::min(smin, c.dot(e));
      smax = std::max(smax, c.dot(e));
    }
    for (double s = smin; s <= smax + 1e-9; s += kPartSeedCell) {
      for (double t = tmin; t <= tmax + 1e-9;) {
        const Eigen::Vector2d x = t * d + s * e;
        double lo = 0.0, hi = 0.0, top = 0.0;
        chord(f, x.x(), x.y(), d.x(), d.y(), lo, hi, top);
        if (hi <= lo) {
          t += kPartSeedCell;
          continue;
        }
        const Eigen::Vector2d m = x + 0.5 * (lo + hi) * d;
        Part part{m, a, 0.0, top};
        bool parallel = true;
        double ulo = lo - 0.5 * (lo + hi), uhi = hi - 0.5 * (lo + hi);
        for (const double o : {-half_width, half_width}) {
          const Eigen::Vector2d y = m + o * e;
          double l2 = 0.0, h2 = 0.0, t2 = 0.0;
          chord(f, y.x(), y.y(), d.x(), d.y(), l2, h2, t2);
          if (!(h2 > l2)) continue;  // the finger's side beyond the part's edge
          parallel = parallel && std::abs(l2 - ulo) <= kPartSeedTaper && std::abs(h2 - uhi) <= kPartSeedTaper;
          ulo = std::min(ulo, l2);
          uhi = std::max(uhi, h2);
          part.top = std::max(part.top, t2);
        }
        part.width = uhi - ulo;
        part.middle = m + 0.5 * (ulo + uhi) * d;
        if (parallel) out.push_back(part);
        t += hi + kPartSeedCell;  // past this chord's end
      }
    }
  }
  return out;
}

/// A part's width and middle measured along its own direction: the extent of the footprint's occupied cells under
/// the fingers (within half_width across, and a cell beyond the part's ends along), each cell's centre and half a
/// cell either way. The chords step cell by cell, so their widths are the same a few degrees off the narrowest
/// direction; the cells' projections are not.
void refine(Part& part, const std::vector<Eigen::Vector2d>& cells, double half_width) {
  const Eigen::Vector2d d(std::cos(part.angle), std::sin(part.angle)), e(-d.y(), d.x());
  const double reach = 0.5 * part.width + kPartSeedCell;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Eigen::Vector2d& c : cells) {
    const Eigen::Vector2d x = c - part.middle;
    const double t = x.dot(d);
    if (std::abs(x.dot(e)) > half_width || std::abs(t) > reach) continue;
    lo = std::min(lo, t);
    hi = std::max(hi, t);
  }
  if (!(hi >= lo)) return;
  part.width = hi - lo + kPartSeedCell;
  part.middle += 0.5 * (lo + hi) * d;
}

/// The part seeds of an object wider than the hand opens: of its parallel parts (parallel_parts, refine) within the
/// widest gap, the narrowest first, up to kPartSeedCentres whose middles lie kPartSeedSpacing apart; each seeded
/// over its middle along its direction, under its own top, at the configurations whose gap is at least its width
/// and at most kPartSeedSlack more (the narrowest wider one if none).
void add_part_seeds(SeedGrasps& out, const HandAtGrasp& h, const RowMatrixXd& openings, const Vec3Array& points,
                    const Eigen::Vector3d& up, double offset, const Eigen::Vector3d& e1, const Eigen::Vector3d& e2) {
  const Eigen::VectorXd u = points * e1, v = points * e2, z = (points * up).array() + offset;
  const Footprint f = footprint(u, v, z);
  std::vector<Eigen::Vector2d> cells;
  for (int j = 0; j < f.nv; ++j)
    for (int i = 0; i < f.nu; ++i)
      if (f.top[static_cast<std::size_t>(j * f.nu + i)] > -std::numeric_limits<double>::infinity())
        cells.emplace_back(f.u0 + (i + 0.5) * kPartSeedCell, f.v0 + (j + 0.5) * kPartSeedCell);
  const double widest = *std::max_element(h.gaps.begin(), h.gaps.end());
  std::vector<Part> parts = parallel_parts(f, cells, h.half_width);
  for (Part& p : parts) refine(p, cells, h.half_width);
  parts.erase(std::remove_if(parts.begin(), parts.end(), [&](const Part& p) { return p.width > widest; }), parts.end());
  std::stable_sort(parts.begin(), parts.end(), [](const Part& a, const Part& b) { return a.width < b.width; });
  std::vector<Eigen::Vector2d> chosen;
  for (const Part& part : parts) {
    if (static_cast<int>(chosen.size()) >= kPartSeedCentres) break;
    if (std::any_of(chosen.begin(), chosen.end(),
                    [&](const Eigen::Vector2d& c) { return (c - part.middle).norm() < kPartSeedSpacing; }))
      continue;
    chosen.push_back(part.middle);
    std::vector<Eigen::Index> rows;
    Eigen::Index narrowest_wider = -1;
    for (Eigen::Index k = 0; k < openings.rows(); ++k) {
      const double s = h.gaps[static_cast<std::size_t>(k)];
      if (s >= part.width && s <= part.width + kPartSeedSlack) rows.push_back(k);
      if (s >= part.width && (narrowest_wider < 0 || s < h.gaps[static_cast<std::size_t>(narrowest_wider)]))
        narrowest_wider = k;
    }
    if (rows.empty()) rows.push_back(narrowest_wider);
    const Eigen::Vector3d n = std::cos(part.angle) * e1 + std::sin(part.angle) * e2;
    const Eigen::Vector3d centre = part.middle.x() * e1 + part.middle.y() * e2 - offset * up;
    add_seeds(out, h, openings, rows, up, n, centre, part.top);
  }
}

}  // namespace

SeedGrasps topdown_seeds(const Hand& hand, const ConfigModel& config, const Vec3Array& points,
                         const Eigen::Vector4d& plane) {
  SeedGrasps out;
  out.wrists.resize(0, 7);
  out.joints.resize(0, hand.n_dofs());
  const double norm = plane.head<3>().norm();
  HandAtGrasp h;
  if (points.rows() < 3 || hand.fingertips().empty() || !(norm > 0.0) || !hand_at_grasp(hand, config, h)) return out;
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
  // An object wider than the hand's widest gap: its parts too.
  if (hi - lo > *std::max_element(h.gaps.begin(), h.gaps.end()))
    add_part_seeds(out, h, openings, points, up, offset, e1, e2);
  return out;
}

}  // namespace graspmix
