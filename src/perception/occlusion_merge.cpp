#include "occlusion_merge.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <numeric>
#include <utility>
#include <vector>

#include "cluster_merge.hpp"
#include "core/parallel_rows.hpp"

namespace graspmix::detail {

namespace {

constexpr double kFacingBand = 0.005;  ///< m beyond the least gap that still counts a point as facing the other
constexpr std::size_t kMaxSegments = 16;
constexpr int kSamples = 9;                 ///< interior samples of a segment, at 0.1, 0.2, ..., 0.9
constexpr std::size_t kMaxPairs = 1000000;  ///< point pairs compared for one cluster pair (then strided)

struct Box {
  Eigen::Vector3d lo, hi;
};

Box bounds(const Vec3Array& P, const std::vector<int>& rows) {
  Box b{Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()),
        Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity())};
  for (const int r : rows) {
    b.lo = b.lo.cwiseMin(P.row(r).transpose());
    b.hi = b.hi.cwiseMax(P.row(r).transpose());
  }
  return b;
}

/// The rows of `rows` within `margin` of box b.
std::vector<int> near_box(const Vec3Array& P, const std::vector<int>& rows, const Box& b, double margin) {
  std::vector<int> out;
  for (const int r : rows) {
    const Eigen::Vector3d p = P.row(r).transpose();
    if ((p.array() >= b.lo.array() - margin).all() && (p.array() <= b.hi.array() + margin).all()) out.push_back(r);
  }
  return out;
}

/// The largest signed distance at a segment's interior samples; -inf where every sample is unseen (NaN).
double most_seen(const VisibilityModel& vis, const Eigen::Vector3d& p0, const Eigen::Vector3d& p1) {
  double best = -std::numeric_limits<double>::infinity();
  for (int k = 1; k <= kSamples; ++k) {
    const double d = vis.signed_distance(p0 + (p1 - p0) * (static_cast<double>(k) / (kSamples + 1)));
    if (!std::isnan(d)) best = std::max(best, d);
  }
  return best;
}

}  // namespace

double largest_side(const Vec3Array& P, const std::vector<int>& rows) {
  Eigen::Vector3d centroid;
  Eigen::Matrix3d axes;
  principal_axes(P, rows, centroid, axes);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const int r : rows) {
    const Eigen::Vector3d q = axes.transpose() * (P.row(r).transpose() - centroid);
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  return (hi - lo).maxCoeff();
}

double seen_beyond_gap(const Vec3Array& P, const VisibilityModel& vis, const std::vector<int>& a,
                       const std::vector<int>& b, double max_gap, double& gap) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  gap = std::numeric_limits<double>::infinity();
  std::vector<int> na = near_box(P, a, bounds(P, b), max_gap), nb = near_box(P, b, bounds(P, a), max_gap);
  if (na.empty() || nb.empty()) return nan;
  if (na.size() > nb.size()) na.swap(nb);
  const std::size_t stride = std::max<std::size_t>(1, na.size() * nb.size() / kMaxPairs);
  std::vector<std::pair<double, std::pair<int, int>>> nearest;  // per point of na: distance, (its row, nearest)
  for (std::size_t i = 0; i < na.size(); i += stride) {
    double best = std::numeric_limits<double>::infinity();
    int arg = -1;
    for (const int r : nb) {
      const double d = (P.row(na[i]) - P.row(r)).squaredNorm();
      if (d < best) best = d, arg = r;
    }
    nearest.push_back({std::sqrt(best), {na[i], arg}});
  }
  std::sort(nearest.begin(), nearest.end());
  gap = nearest.front().first;
  if (gap > max_gap) return nan;
  std::vector<double> seen;
  for (const auto& [d, rows] : nearest) {
    if (d > gap + kFacingBand || seen.size() == kMaxSegments) break;
    seen.push_back(most_seen(vis, P.row(rows.first).transpose(), P.row(rows.second).transpose()));
  }
  std::nth_element(seen.begin(), seen.begin() + static_cast<std::ptrdiff_t>(seen.size() / 2), seen.end());
  return seen[seen.size() / 2];
}

std::size_t join_occluded(const Vec3Array& P, const VisibilityModel& vis, std::vector<std::vector<int>>& groups,
                          const JoinRule& rule) {
  const double inf = std::numeric_limits<double>::infinity();
  // gaps[i][j] (i < j): the least gap of a pair that passes the rule, inf when it does not (kept until i or
  // j changes)
  std::vector<std::vector<double>> gaps;
  const auto judge = [&](std::size_t i, std::size_t j) {
    double gap = inf;
    const double seen = seen_beyond_gap(P, vis, groups[i], groups[j], rule.max_gap, gap);
    if (!(seen <= rule.seen_margin)) return inf;  // also NaN: too far apart
    std::vector<int> both;
    std::merge(groups[i].begin(), groups[i].end(), groups[j].begin(), groups[j].end(), std::back_inserter(both));
    return largest_side(P, both) <= rule.max_size ? gap : inf;
  };
  gaps.assign(groups.size(), std::vector<double>(groups.size(), inf));
  std::vector<std::pair<std::size_t, std::size_t>> pairs;  // every pair judged once, each on a thread as one comes free
  for (std::size_t i = 0; i < groups.size(); ++i)
    for (std::size_t j = i + 1; j < groups.size(); ++j) pairs.emplace_back(i, j);
  parallel_rows<NoState>(
      static_cast<std::int64_t>(pairs.size()),
      [&](NoState&, std::int64_t k) {
        const auto [i, j] = pairs[static_cast<std::size_t>(k)];
        gaps[i][j] = judge(i, j);
      },
      RowOrder::AsThreadsFree);
  std::size_t joins = 0;
  for (;;) {
    std::size_t bi = 0, bj = 0;
    double best = inf;
    for (std::size_t i = 0; i < groups.size(); ++i)
      for (std::size_t j = i + 1; j < groups.size(); ++j)
        if (gaps[i][j] < best) best = gaps[i][j], bi = i, bj = j;
    if (best == inf) return joins;
    std::vector<int> both;
    std::merge(groups[bi].begin(), groups[bi].end(), groups[bj].begin(), groups[bj].end(), std::back_inserter(both));
    groups[bi] = std::move(both);
    groups.erase(groups.begin() + static_cast<std::ptrdiff_t>(bj));
    gaps.erase(gaps.begin() + static_cast<std::ptrdiff_t>(bj));
    for (auto& row : gaps) row.erase(row.begin() + static_cast<std::ptrdiff_t>(bj));
    for (std::size_t k = 0; k < groups.size(); ++k)
      if (k != bi) gaps[std::min(k, bi)][std::max(k, bi)] = judge(std::min(k, bi), std::max(k, bi));
    ++joins;
  }
}

}  // namespace graspmix::detail
