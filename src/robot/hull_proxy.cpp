// The proxy box of a mesh's convex hull and the bound that lets the experts decide most points with it.
#include "robot/hull_proxy.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <Eigen/Eigenvalues>

namespace graspmix::detail {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kBoxMargin = 1e-9;  // m: the box's sides stand this far off the hull, against rounding
constexpr double kDualSlack = 1e-9;  // a dual weight this far below 0 still counts as >= 0 (rounding)
constexpr size_t kMaxIncident = 48;  // planes at one vertex tried for the bound (C(48, 3) triples at most)

/// The box around the rows of V with axes the columns of R: its centre (shape frame), half extents and volume.
double fit_box(const Vec3Array& V, const Eigen::Matrix3d& R, Eigen::Vector3d& centre, Eigen::Vector3d& half) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(kInf), hi = -lo;
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    const Eigen::Vector3d q = R.transpose() * V.row(i).transpose();
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  centre = R * (0.5 * (lo + hi));
  half = (0.5 * (hi - lo)).array() + kBoxMargin;
  return half.prod();
}

/// The least sum of weights y >= 0 with sum_f y_f n_f = u over three of the planes F (rows of P): for a vertex v
/// on all of them, every x with n . x <= offset + g on every plane has u . x <= u . v + g * sum(y). inf if none.
double dual_sum(const RowMatrixXd& P, const std::vector<int>& F, const Eigen::Vector3d& u) {
  double best = kInf;
  const size_t n = std::min(F.size(), kMaxIncident);
  for (size_t a = 0; a < n; ++a)
    for (size_t b = a + 1; b < n; ++b)
      for (size_t c = b + 1; c < n; ++c) {
        Eigen::Matrix3d M;
        M.col(0) = P.row(F[a]).head<3>().transpose();
        M.col(1) = P.row(F[b]).head<3>().transpose();
        M.col(2) = P.row(F[c]).head<3>().transpose();
        if (!(std::abs(M.determinant()) > 1e-13)) continue;
        const Eigen::Vector3d y = M.inverse() * u;
        if (y.minCoeff() >= -kDualSlack) best = std::min(best, y.cwiseMax(0.0).sum());
      }
  return best;
}

/// The largest s in [0, 1] (to 1e-6) such that the box (centre, axes R, half extents s * half) has its eight
/// corners, and so all of it, inside every plane.
double inner_scale(const RowMatrixXd& P, const Eigen::Matrix3d& R, const Eigen::Vector3d& centre,
                   const Eigen::Vector3d& half) {
  const auto inside = [&](double sc) {
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector3d corner(c & 1 ? 1.0 : -1.0, c & 2 ? 1.0 : -1.0, c & 4 ? 1.0 : -1.0);
      const Eigen::Vector3d x = centre + R * (sc * half.cwiseProduct(corner));
      for (Eigen::Index f = 0; f < P.rows(); ++f) {
        if (P(f, 0) * x.x() + P(f, 1) * x.y() + P(f, 2) * x.z() - P(f, 3) > 0.0) return false;
      }
    }
    return true;
  };
  double lo = 0.0, hi = 1.0;
  while (hi - lo > 1e-6) {
    const double m = 0.5 * (lo + hi);
    (inside(m) ? lo : hi) = m;
  }
  return lo;
}

}  // namespace

void fit_hull_proxy(RowMatrixXd& planes, const TriangleMesh& hull, const std::vector<int>& tri_plane,
                    CollisionShape& s) {
  const Vec3Array& V = hull.vertices;
  const auto P = static_cast<size_t>(planes.rows());
  // Largest facet first: a point outside the hull is then most often told by the first planes.
  std::vector<double> area(P, 0.0);
  for (Eigen::Index t = 0; t < hull.triangles.rows(); ++t) {
    const Eigen::Vector3d a = V.row(hull.triangles(t, 0)), b = V.row(hull.triangles(t, 1)),
                          c = V.row(hull.triangles(t, 2));
    area[static_cast<size_t>(tri_plane[static_cast<size_t>(t)])] += 0.5 * (b - a).cross(c - a).norm();
  }
  std::vector<int> order(P), rank(P);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int i, int j) { return area[i] > area[j]; });
  RowMatrixXd sorted(planes.rows(), 4);
  for (size_t i = 0; i < P; ++i) {
    sorted.row(static_cast<Eigen::Index>(i)) = planes.row(order[i]);
    rank[static_cast<size_t>(order[i])] = static_cast<int>(i);
  }
  planes = std::move(sorted);
  // The box: along the shape's axes or along the vertices' principal axes, whichever is smaller.
  const Eigen::RowVector3d mean = V.colwise().mean();
  const Eigen::Matrix3d cov = (V.rowwise() - mean).transpose() * (V.rowwise() - mean);
  Eigen::Matrix3d R = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(cov).eigenvectors();
  if (R.determinant() < 0) R.col(2) = -R.col(2);
  Eigen::Vector3d centre, half, c2, h2;
  if (fit_box(V, Eigen::Matrix3d::Identity(), c2, h2) <= fit_box(V, R, centre, half)) {
    R.setIdentity();
    centre = c2;
    half = h2;
  }
  s.T_shape_box = Eigen::Isometry3d::Identity();
  s.T_shape_box.linear() = R;
  s.T_shape_box.translation() = centre;
  s.box_half = half;
  s.box_inner = inner_scale(planes, R, centre, half.array() - kBoxMargin) * (half.array() - kBoxMargin).matrix();
  // The growth: for each side's normal u, the extreme vertex's planes give the bound (hull_proxy.hpp).
  std::vector<std::vector<int>> incident(static_cast<size_t>(V.rows()));
  for (Eigen::Index t = 0; t < hull.triangles.rows(); ++t)
    for (int k = 0; k < 3; ++k) {
      std::vector<int>& inc = incident[static_cast<size_t>(hull.triangles(t, k))];
      const int row = rank[static_cast<size_t>(tri_plane[static_cast<size_t>(t)])];
      if (std::find(inc.begin(), inc.end(), row) == inc.end()) inc.push_back(row);
    }
  double growth = 1.0;
  for (int k = 0; k < 6; ++k) {
    const Eigen::Vector3d u = (k < 3 ? 1.0 : -1.0) * R.col(k % 3);
    Eigen::Index v = 0;
    (V * u).maxCoeff(&v);
    growth = std::max(growth, dual_sum(planes, incident[static_cast<size_t>(v)], u));
  }
  s.box_growth = growth * (1.0 + 1e-9);
}

}  // namespace graspmix::detail
