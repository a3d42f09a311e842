#include "cluster_merge.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <numeric>

#include <Eigen/Eigenvalues>

namespace graspmix::detail {

namespace {

/// The 13 slab normals of a 26-DOP in the frame `axes`: the axes, their 6 face and 4 body diagonals.
Eigen::Matrix<double, 3, 13> dop_normals(const Eigen::Matrix3d& axes) {
  Eigen::Matrix<double, 3, 13> n;
  int k = 0;
  for (int i = 0; i < 3; ++i) n.col(k++) = Eigen::Vector3d::Unit(i);
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j)
      for (const double sgn : {1.0, -1.0})
        n.col(k++) = (Eigen::Vector3d::Unit(i) + sgn * Eigen::Vector3d::Unit(j)) / std::sqrt(2.0);
  for (const double s1 : {1.0, -1.0})
    for (const double s2 : {1.0, -1.0}) n.col(k++) = Eigen::Vector3d(1.0, s1, s2) / std::sqrt(3.0);
  return axes * n;
}

}  // namespace

void principal_axes(const Vec3Array& P, const std::vector<int>& rows, Eigen::Vector3d& centroid,
                    Eigen::Matrix3d& axes) {
  Vec3Array Q(static_cast<Eigen::Index>(rows.size()), 3);
  for (std::size_t i = 0; i < rows.size(); ++i) Q.row(static_cast<Eigen::Index>(i)) = P.row(rows[i]);
  centroid = Q.colwise().mean().transpose();
  const Vec3Array C = Q.rowwise() - centroid.transpose();
  const Eigen::Matrix3d cov = C.transpose() * C / static_cast<double>(rows.size());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  axes = eig.eigenvectors().rowwise().reverse();  // decreasing variance
  for (int k = 0; k < 2; ++k) {
    Eigen::Index big = 0;
    axes.col(k).cwiseAbs().maxCoeff(&big);
    if (axes(big, k) < 0) axes.col(k) = -axes.col(k);
  }
  axes.col(2) = axes.col(0).cross(axes.col(1));
}

double seen_through(const Vec3Array& P, const Vec3Array& cameras, const std::vector<int>& b, const std::vector<int>& a,
                    double inset) {
  Eigen::Vector3d centroid;
  Eigen::Matrix3d axes;
  principal_axes(P, b, centroid, axes);
  const Eigen::Matrix<double, 3, 13> n = dop_normals(axes);
  Eigen::Array<double, 1, 13> lo = Eigen::Array<double, 1, 13>::Constant(std::numeric_limits<double>::infinity());
  Eigen::Array<double, 1, 13> hi = -lo;
  for (const int r : b) {
    const Eigen::Array<double, 1, 13> proj = (P.row(r) * n).array();
    lo = lo.min(proj);
    hi = hi.max(proj);
  }
  lo += inset;
  hi -= inset;
  std::size_t crossing = 0;
  for (const int r : a) {
    const auto cam = cameras.row(cameras.rows() == 1 ? 0 : r);
    const Eigen::Array<double, 1, 13> c = (cam * n).array(), v = ((P.row(r) - cam) * n).array();
    double enter = 0.0, leave = 1.0;  // the segment camera -> point, clipped slab by slab
    for (int k = 0; k < 13 && enter < leave; ++k) {
      if (v[k] == 0.0) {
        if (c[k] < lo[k] || c[k] > hi[k]) leave = -1.0;
        continue;
      }
      const double t1 = (lo[k] - c[k]) / v[k], t2 = (hi[k] - c[k]) / v[k];
      enter = std::max(enter, std::min(t1, t2));
      leave = std::min(leave, std::max(t1, t2));
    }
    if (enter < leave) ++crossing;
  }
  return static_cast<double>(crossing) / static_cast<double>(a.size());
}

std::size_t merge_seen_through(const Vec3Array& P, const Vec3Array& cameras, std::vector<std::vector<int>>& groups,
                               double fraction, double inset) {
  std::size_t joins = 0;
  for (bool joined = true; joined;) {
    joined = false;
    std::vector<std::size_t> order(groups.size());  // by decreasing size, ties by first row
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
      if (groups[x].size() != groups[y].size()) return groups[x].size() > groups[y].size();
      return groups[x].front() < groups[y].front();
    });
    for (std::size_t i = order.size(); i-- > 1 && !joined;) {
      for (std::size_t j = 0; j < i && !joined; ++j) {
        const std::size_t small = order[i], big = order[j];
        if (groups[big].size() <= groups[small].size()) break;
        if (seen_through(P, cameras, groups[big], groups[small], inset) < fraction) continue;
        std::vector<int> both;
        std::merge(groups[big].begin(), groups[big].end(), groups[small].begin(), groups[small].end(),
                   std::back_inserter(both));
        groups[big] = std::move(both);
        groups.erase(groups.begin() + static_cast<std::ptrdiff_t>(small));
        joined = true;
        ++joins;
      }
    }
  }
  return joins;
}

}  // namespace graspmix::detail
