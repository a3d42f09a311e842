#include "grasp/object_parts.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "graspmix/grasp/topdown_seeds.hpp"

namespace graspmix {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// The object's footprint on the table in cells of kPartSeedCell (u, v: coordinates along e1, e2): which points fall
/// in each cell (their indices, cell by cell, u fastest) and the highest above it.
struct Footprint {
  double u0 = 0.0, v0 = 0.0;
  long nu = 0, nv = 0;
  std::vector<double> top;          ///< per cell, -inf where no point
  std::vector<Eigen::Index> start;  ///< per cell, into `index`; start[c + 1] ends it
  std::vector<Eigen::Index> index;  ///< the points, cell by cell
  Eigen::VectorXd u, v, z;          ///< every point's coordinates and height

  /// The cell of (x, y), or -1 outside the grid.
  long cell(double x, double y) const {
    const double i = std::floor((x - u0) / kPartSeedCell), j = std::floor((y - v0) / kPartSeedCell);
    if (!(i >= 0 && j >= 0 && i < static_cast<double>(nu) && j < static_cast<double>(nv))) return -1;
    return static_cast<long>(j) * nu + static_cast<long>(i);
  }
  bool occupied(double x, double y) const {
    const long c = cell(x, y);
    return c >= 0 && top[static_cast<std::size_t>(c)] > -kInf;
  }
};

/// The footprint of the points (u, v, z), or false when it would have more than kPartSeedMaxCells cells.
bool make_footprint(Eigen::VectorXd u, Eigen::VectorXd v, Eigen::VectorXd z, Footprint& f) {
  f.u0 = u.minCoeff();
  f.v0 = v.minCoeff();
  const double su = (u.maxCoeff() - f.u0) / kPartSeedCell + 1.0, sv = (v.maxCoeff() - f.v0) / kPartSeedCell + 1.0;
  if (!(su * sv <= static_cast<double>(kPartSeedMaxCells))) return false;
  f.nu = static_cast<long>(su);
  f.nv = static_cast<long>(sv);
  const std::size_t cells = static_cast<std::size_t>(f.nu * f.nv);
  f.top.assign(cells, -kInf);
  f.start.assign(cells + 1, 0);
  std::vector<long> of(static_cast<std::size_t>(u.size()));
  for (Eigen::Index i = 0; i < u.size(); ++i) {
    const long a = std::min(f.nu - 1, static_cast<long>((u[i] - f.u0) / kPartSeedCell));
    const long b = std::min(f.nv - 1, static_cast<long>((v[i] - f.v0) / kPartSeedCell));
    const std::size_t c = static_cast<std::size_t>(b * f.nu + a);
    of[static_cast<std::size_t>(i)] = static_cast<long>(c);
    f.top[c] = std::max(f.top[c], z[i]);
    ++f.start[c + 1];
  }
  for (std::size_t c = 0; c < cells; ++c) f.start[c + 1] += f.start[c];
  f.index.resize(static_cast<std::size_t>(u.size()));
  std::vector<Eigen::Index> fill(f.start.begin(), f.start.end() - 1);
  for (Eigen::Index i = 0; i < u.size(); ++i)
    f.index[static_cast<std::size_t>(fill[static_cast<std::size_t>(of[static_cast<std::size_t>(i)])]++)] = i;
  f.u = std::move(u);
  f.v = std::move(v);
  f.z = std::move(z);
  return true;
}

/// Whether any of the points (u, v) lies within kPartSeedIsolation of an occupied cell (the cells' squares).
bool anything_near(const Footprint& f, const Eigen::VectorXd& u, const Eigen::VectorXd& v) {
  const long r = static_cast<long>(std::ceil(kPartSeedIsolation / kPartSeedCell));
  for (Eigen::Index k = 0; k < u.size(); ++k) {
    const double i = std::floor((u[k] - f.u0) / kPartSeedCell), j = std::floor((v[k] - f.v0) / kPartSeedCell);
    if (!(i >= -r && j >= -r && i < static_cast<double>(f.nu + r) && j < static_cast<double>(f.nv + r))) continue;
    for (long b = std::max(0L, static_cast<long>(j) - r); b <= std::min(f.nv - 1, static_cast<long>(j) + r); ++b)
      for (long a = std::max(0L, static_cast<long>(i) - r); a <= std::min(f.nu - 1, static_cast<long>(i) + r); ++a) {
        if (f.top[static_cast<std::size_t>(b * f.nu + a)] == -kInf) continue;
        const double du = std::max({0.0, f.u0 + a * kPartSeedCell - u[k], u[k] - (f.u0 + (a + 1) * kPartSeedCell)});
        const double dv = std::max({0.0, f.v0 + b * kPartSeedCell - v[k], v[k] - (f.v0 + (b + 1) * kPartSeedCell)});
        if (du * du + dv * dv <= kPartSeedIsolation * kPartSeedIsolation) return true;
      }
  }
  return false;
}

/// The chord of the footprint through (x, y) along the unit direction d: from the point, outwards both ways, cell
/// by cell until two cells in a row hold no point; its ends along d (each half a cell beyond the last occupied
/// cell). False from a cell that holds no point.
bool chord(const Footprint& f, const Eigen::Vector2d& x, const Eigen::Vector2d& d, double& lo, double& hi) {
  if (!f.occupied(x.x(), x.y())) return false;
  for (const double sign : {-1.0, 1.0}) {
    double last = 0.0;
    for (int step = 1, empty = 0; empty < 2; ++step) {
      const Eigen::Vector2d y = x + sign * step * kPartSeedCell * d;
      if (!f.occupied(y.x(), y.y())) {
        ++empty;
        continue;
      }
      empty = 0;
      last = sign * step * kPartSeedCell;
    }
    (sign < 0 ? lo : hi) = last + sign * 0.5 * kPartSeedCell;
  }
  return true;
}

/// A candidate part in footprint coordinates: middle, direction and width (rough, then refined).
struct Part {
  Eigen::Vector2d middle, direction;
  double width = 0.0, top = 0.0;
};

/// Every chord of the footprint's lines half a cell apart along each of kPartSeedDirections directions, as a part
/// (middle, direction, rough width) when the rough width is at most `widest` and a cell.
std::vector<Part> chords_within(const Footprint& f, double widest) {
  std::vector<Part> out;
  for (int k = 0; k < kPartSeedDirections; ++k) {
    const double a = k * M_PI / kPartSeedDirections;
    const Eigen::Vector2d d(std::cos(a), std::sin(a)), e(-d.y(), d.x());
    double tmin = kInf, tmax = -kInf, smin = kInf, smax = -kInf;
    for (const double cu : {f.u0, f.u0 + f.nu * kPartSeedCell})
      for (const double cv : {f.v0, f.v0 + f.nv * kPartSeedCell}) {
        const Eigen::Vector2d c(cu, cv);
        tmin = std::min(tmin, c.dot(d));
        tmax = std::max(tmax, c.dot(d));
        smin = std::min(smin, c.dot(e));
        smax = std::max(smax, c.dot(e));
      }
    for (double s = smin; s <= smax; s += 0.5 * kPartSeedCell) {
      for (double t = tmin; t <= tmax;) {
        const Eigen::Vector2d x = t * d + s * e;
        double lo = 0.0, hi = 0.0;
        if (!chord(f, x, d, lo, hi)) {
          t += kPartSeedCell;
          continue;
        }
        if (hi - lo <= widest + kPartSeedCell) out.push_back(Part{x + 0.5 * (lo + hi) * d, d, hi - lo, 0.0});
        t += hi + kPartSeedCell;  // past this chord's end
      }
    }
  }
  return out;
}

/// A chord measured from the points (within a cell beyond its rough ends along; the side lines farther): on three
/// lines along its direction, its middle line and half_width to either side, the extent of the points within half a
/// cell of each; the part has facing walls when the middle line and at least one side line hold points and every
/// side line that does ends within kPartSeedTaper of the middle line's ends (a corner's diagonal has a side line
/// inside that ends elsewhere; a side line beyond the part's edge holds none: the finger overhangs it). Then its
/// width is the extent of the lines that hold points (what the fingers span), its middle between those ends, its
/// top the highest point under the fingers (within half_width across). False otherwise.
bool measure(const Footprint& f, double half_width, Part& p) {
  const Eigen::Vector2d e(-p.direction.y(), p.direction.x());
  // The middle line within a cell of the rough ends; the side lines farther, so that one running on is seen to.
  const double reach = 0.5 * p.width + kPartSeedCell, side_reach = reach + kPartSeedTaper + kPartSeedCell;
  const double r = side_reach + half_width;
  double lo[3] = {kInf, kInf, kInf}, hi[3] = {-kInf, -kInf, -kInf}, top = -kInf;
  const long i0 = std::max(0L, static_cast<long>(std::floor((p.middle.x() - r - f.u0) / kPartSeedCell)));
  const long i1 = std::min(f.nu - 1, static_cast<long>(std::floor((p.middle.x() + r - f.u0) / kPartSeedCell)));
  const long j0 = std::max(0L, static_cast<long>(std::floor((p.middle.y() - r - f.v0) / kPartSeedCell)));
  const long j1 = std::min(f.nv - 1, static_cast<long>(std::floor((p.middle.y() + r - f.v0) / kPartSeedCell)));
  for (long j = j0; j <= j1; ++j)
    for (long i = i0; i <= i1; ++i) {
      const std::size_t c = static_cast<std::size_t>(j * f.nu + i);
      for (Eigen::Index k = f.start[c]; k < f.start[c + 1]; ++k) {
        const Eigen::Index q = f.index[static_cast<std::size_t>(k)];
        const Eigen::Vector2d x = Eigen::Vector2d(f.u[q], f.v[q]) - p.middle;
        const double t = x.dot(p.direction), across = x.dot(e);
        if (std::abs(t) > side_reach) continue;
        if (std::abs(t) <= reach && std::abs(across) <= half_width) top = std::max(top, f.z[q]);
        for (int l = 0; l < 3; ++l) {
          if (std::abs(across - (l - 1) * half_width) > 0.5 * kPartSeedCell || (l == 1 && std::abs(t) > reach))
            continue;
          lo[l] = std::min(lo[l], t);
          hi[l] = std::max(hi[l], t);
        }
      }
    }
  if (!(hi[1] >= lo[1]) || !(hi[0] >= lo[0] || hi[2] >= lo[2])) return false;
  for (const int l : {0, 2})
    if (hi[l] >= lo[l] && (std::abs(lo[l] - lo[1]) > kPartSeedTaper || std::abs(hi[l] - hi[1]) > kPartSeedTaper))
      return false;
  double first = lo[1], last = hi[1];
  for (const int l : {0, 2})
    if (hi[l] >= lo[l]) {
      first = std::min(first, lo[l]);
      last = std::max(last, hi[l]);
    }
  p.width = last - first;
  p.middle += 0.5 * (first + last) * p.direction;
  p.top = top;
  return true;
}

}  // namespace

std::vector<ObjectPart> graspable_parts(const Vec3Array& points, const Vec3Array& others, const Eigen::Vector3d& up,
                                        double offset, double half_width, double widest) {
  const Eigen::Vector3d e1 = up.unitOrthogonal(), e2 = up.cross(e1);
  Footprint f;
  if (points.rows() == 0 || !make_footprint(points * e1, points * e2, (points * up).array() + offset, f)) return {};
  if (others.rows() > 0 && anything_near(f, others * e1, others * e2)) return {};
  std::vector<Part> parts = chords_within(f, widest);
  parts.erase(std::remove_if(parts.begin(), parts.end(),
                             [&](Part& p) { return !measure(f, half_width, p) || !(p.width <= widest); }),
              parts.end());
  std::stable_sort(parts.begin(), parts.end(), [](const Part& a, const Part& b) { return a.width < b.width; });
  std::vector<ObjectPart> out;
  for (const Part& p : parts) {
    if (static_cast<int>(out.size()) >= kPartSeedCentres) break;
    const Eigen::Vector3d middle = p.middle.x() * e1 + p.middle.y() * e2 - offset * up;
    if (std::any_of(out.begin(), out.end(),
                    [&](const ObjectPart& o) { return (o.middle - middle).norm() < kPartSeedSpacing; }))
      continue;
    out.push_back(ObjectPart{middle, p.direction.x() * e1 + p.direction.y() * e2, p.width, p.top});
  }
  return out;
}

}  // namespace graspmix
