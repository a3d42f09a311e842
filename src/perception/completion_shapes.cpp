// complete_object's shapes: the table frame, the footprint, normals, mirror, revolution and extrusion.
#include "perception/completion_shapes.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>

#include "core/uniform_grid.hpp"

namespace graspmix::detail {

namespace {
constexpr double kTwoPi = 6.283185307179586;
}  // namespace

TableFrame::TableFrame(const Eigen::Ref<const Vec3Array>& P, const Eigen::Vector4d& plane,
                       const Eigen::Vector3d& viewpoint)
    : n(plane.head<3>()), d(plane[3]) {
  Eigen::Index k = 0;
  n.cwiseAbs().minCoeff(&k);
  e1 = n.cross(Eigen::Vector3d::Unit(k)).normalized();
  e2 = n.cross(e1);
  u.resize(P.rows(), 2);
  h.resize(P.rows());
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    const Eigen::Vector3d p = P.row(i).transpose();
    u.row(i) << p.dot(e1), p.dot(e2);
    h[i] = n.dot(p) + d;
  }
  camera << viewpoint.dot(e1), viewpoint.dot(e2);
}

Footprint::Footprint(const TableFrame& f, double cell_size) : cell(cell_size) {
  const Eigen::Vector2d lo = f.u.colwise().minCoeff().transpose(), hi = f.u.colwise().maxCoeff().transpose();
  origin = lo - Eigen::Vector2d::Constant(cell);  // one empty cell of padding on every side
  nx = static_cast<int>(std::floor((hi.x() - origin.x()) / cell)) + 2;
  ny = static_cast<int>(std::floor((hi.y() - origin.y()) / cell)) + 2;
  state.assign(static_cast<std::size_t>(nx) * ny, 0);
  top.assign(state.size(), -1);
  for (Eigen::Index i = 0; i < f.u.rows(); ++i) {
    const int ix = static_cast<int>((f.u(i, 0) - origin.x()) / cell),
              iy = static_cast<int>((f.u(i, 1) - origin.y()) / cell);
    const int c = index(ix, iy);
    state[c] = 1;
    if (top[c] < 0 || f.h[i] > f.h[top[c]]) top[c] = static_cast<int>(i);
  }
  // Outside: the empty cells reachable from the padding (a flood fill over 4-neighbours).
  std::vector<int> stack{0};
  state[0] = 2;
  const int step[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
  while (!stack.empty()) {
    const int c = stack.back();
    stack.pop_back();
    for (const auto& s : step) {
      const int x = c % nx + s[0], y = c / nx + s[1];
      if (x < 0 || y < 0 || x >= nx || y >= ny || state[index(x, y)] != 0) continue;
      state[index(x, y)] = 2;
      stack.push_back(index(x, y));
    }
  }
  for (int c = 0; c < nx * ny; ++c) {
    if (state[c] != 1) continue;
    const int x = c % nx, y = c / nx;
    if (outside(x + 1, y) || outside(x - 1, y) || outside(x, y + 1) || outside(x, y - 1)) outline.push_back(c);
  }
}

Vec3Array observed_normals(const Eigen::Ref<const Vec3Array>& P, const Eigen::Vector3d& viewpoint, double radius,
                           const std::vector<Eigen::Index>* rows) {
  const UniformGrid grid = UniformGrid::covering(P, radius);
  // The grid positions of the points asked for: all, or those of `rows`.
  std::vector<int> asked;
  if (rows) {
    std::vector<int> position(static_cast<std::size_t>(P.rows()));
    for (int i = 0; i < grid.size(); ++i) position[static_cast<std::size_t>(grid.row(i))] = i;
    for (const Eigen::Index r : *rows) asked.push_back(position[static_cast<std::size_t>(r)]);
  } else {
    asked.resize(static_cast<std::size_t>(grid.size()));
    std::iota(asked.begin(), asked.end(), 0);
  }
  Vec3Array N = Vec3Array::Zero(P.rows(), 3);
  const int n = static_cast<int>(asked.size());
  // Each point's normal on its own: the points in parallel, each thread with its own neighbour lists.
#pragma omp parallel
  {
    std::vector<int> nn;
    std::vector<double> d2;
#pragma omp for schedule(static)
    for (int a = 0; a < n; ++a) {
      const int i = asked[static_cast<std::size_t>(a)];
      grid.neighbours(i, radius * radius, nn, d2);
      Eigen::Vector3d normal = (viewpoint - grid.point(i)).normalized();  // too few neighbours: face the camera
      if (nn.size() >= 3) {
        Eigen::Vector3d mean = Eigen::Vector3d::Zero();
        for (const int j : nn) mean += grid.point(j);
        mean /= static_cast<double>(nn.size());
        Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
        for (const int j : nn) C += (grid.point(j) - mean) * (grid.point(j) - mean).transpose();
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(C);
        normal = es.eigenvectors().col(0);
        if (normal.dot(viewpoint - grid.point(i)) < 0) normal = -normal;
      }
      N.row(grid.row(i)) = normal.transpose();
    }
  }
  return N;
}

Shape mirror_shape(const Eigen::Ref<const Vec3Array>& P, const Vec3Array& N, const Eigen::Vector3d& m, double o) {
  Shape s;
  s.points = P;
  for (Eigen::Index i = 0; i < P.rows(); ++i) s.points.row(i) -= 2 * (P.row(i).dot(m) - o) * m.transpose();
  if (N.rows() == P.rows()) {
    s.normals = N;
    for (Eigen::Index i = 0; i < N.rows(); ++i) s.normals.row(i) -= 2 * N.row(i).dot(m) * m.transpose();
  }
  return s;
}

namespace {

/// Kasa's algebraic circle through points (rows): x^2 + y^2 + D x + E y + F = 0 by least squares.
bool kasa(const std::vector<Eigen::Vector2d>& q, Eigen::Vector2d& centre, double& radius) {
  if (q.size() < 3) return false;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : q) mean += p;
  mean /= static_cast<double>(q.size());
  Eigen::MatrixXd A(static_cast<Eigen::Index>(q.size()), 3);
  Eigen::VectorXd b(A.rows());
  for (Eigen::Index i = 0; i < A.rows(); ++i) {
    const Eigen::Vector2d p = q[static_cast<std::size_t>(i)] - mean;  // centred for conditioning
    A.row(i) << p.x(), p.y(), 1.0;
    b[i] = -p.squaredNorm();
  }
  const Eigen::Vector3d x = A.colPivHouseholderQr().solve(b);
  centre = Eigen::Vector2d(-x[0] / 2, -x[1] / 2);
  const double r2 = centre.squaredNorm() - x[2];
  if (!(r2 > 0) || !centre.allFinite()) return false;
  centre += mean;
  radius = std::sqrt(r2);
  return true;
}

}  // namespace

Circle fit_outline_circle(const TableFrame& f, const Footprint& fp, const CompletionSettings& s) {
  Circle c;
  // Each outline cell's points' mean (the outermost point of a cell would carry the noise's extreme outwards).
  std::vector<Eigen::Vector2d> sum(fp.state.size(), Eigen::Vector2d::Zero());
  std::vector<int> count(fp.state.size(), 0);
  for (Eigen::Index i = 0; i < f.u.rows(); ++i) {
    const int cell = fp.index(static_cast<int>((f.u(i, 0) - fp.origin.x()) / fp.cell),
                              static_cast<int>((f.u(i, 1) - fp.origin.y()) / fp.cell));
    sum[cell] += f.u.row(i).transpose(), ++count[cell];
  }
  std::vector<Eigen::Vector2d> q;
  for (const int cell : fp.outline) q.emplace_back(sum[cell] / count[cell]);
  if (q.size() < 8) return c;
  std::vector<Eigen::Vector2d> in = q;
  const double band = 2 * s.circle_max_rms;
  for (int iteration = 0; iteration < 4; ++iteration) {  // trimmed: refit on the inliers of the last fit
    if (!kasa(in, c.centre, c.radius)) return c;
    in.clear();
    double ss = 0;
    for (const auto& p : q) {
      const double e = (p - c.centre).norm() - c.radius;
      if (std::abs(e) <= std::max(band, iteration == 0 ? 4 * band : band)) in.push_back(p), ss += e * e;
    }
    c.inliers = static_cast<double>(in.size()) / static_cast<double>(q.size());
    c.rms = in.empty() ? 0.0 : std::sqrt(ss / static_cast<double>(in.size()));
  }
  c.ok = c.inliers >= s.circle_min_inliers && c.rms <= s.circle_max_rms && c.radius <= s.max_radius &&
         kasa(in, c.centre, c.radius);
  return c;
}

Shape revolution_shape(const TableFrame& f, const Circle& c, const Vec3Array& N, double spacing) {
  struct Bin {
    double h = 0, r = 0, nr = 0, nh = 0;
    int count = 0;
  };
  std::map<std::pair<long, long>, Bin> bins;  // ordered: the same points whatever the input order's hash
  const double r_max = c.radius + 2 * spacing;
  for (Eigen::Index i = 0; i < f.u.rows(); ++i) {
    const Eigen::Vector2d radial = f.u.row(i).transpose() - c.centre;
    const double h = std::max(f.h[i], 0.0);
    if (radial.norm() > r_max) continue;  // a handle or a neighbour's point: not part of the body of revolution
    const double r = std::min(radial.norm(), c.radius);  // beyond the outline's circle: the noise
    Bin& b = bins[{std::lround(h / spacing), std::lround(r / spacing)}];
    b.h += h, b.r += r, ++b.count;
    if (N.rows() == f.u.rows()) {
      const Eigen::Vector2d er = r > 1e-9 ? Eigen::Vector2d(radial / r) : Eigen::Vector2d::Zero();
      b.nr += N.row(i).dot(f.world_dir(er, 0.0).transpose());
      b.nh += N.row(i).dot(f.n.transpose());
    }
  }
  std::vector<Eigen::Vector3d> pts, nrm;
  for (const auto& [key, b] : bins) {
    const double h = b.h / b.count, r = b.r / b.count;
    const int K = std::max(1, static_cast<int>(std::lround(kTwoPi * r / spacing)));
    Eigen::Vector2d nv(b.nr, b.nh);
    nv = nv.norm() > 1e-9 ? Eigen::Vector2d(nv.normalized()) : Eigen::Vector2d(1, 0);
    for (int k = 0; k < K; ++k) {
      const double phi = kTwoPi * (k + 0.5 * (key.second % 2)) / K;  // alternate rings offset half a step
      const Eigen::Vector2d er(std::cos(phi), std::sin(phi));
      pts.push_back(f.world(c.centre + r * er, h));
      nrm.push_back(f.world_dir(nv.x() * er, nv.y()).normalized());
    }
  }
  Shape s;
  s.points.resize(static_cast<Eigen::Index>(pts.size()), 3);
  s.normals.resize(s.points.rows(), 3);
  for (Eigen::Index i = 0; i < s.points.rows(); ++i) {
    s.points.row(i) = pts[static_cast<std::size_t>(i)].transpose();
    s.normals.row(i) = nrm[static_cast<std::size_t>(i)].transpose();
  }
  return s;
}

Shape extrusion_shape(const TableFrame& f, const Footprint& fp, double spacing, std::vector<Eigen::Index>& starts) {
  const Eigen::Vector2d mid = f.u.colwise().mean().transpose();
  std::vector<Eigen::Vector3d> pts, nrm;
  starts.clear();
  for (const int cell : fp.outline) {
    starts.push_back(static_cast<Eigen::Index>(pts.size()));
    const int row = fp.top[cell], x = cell % fp.nx, y = cell / fp.nx;
    Eigen::Vector2d out = Eigen::Vector2d::Zero();  // towards the outside neighbours
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        if ((dx || dy) && fp.outside(x + dx, y + dy)) out += Eigen::Vector2d(dx, dy).normalized();
    const Eigen::Vector2d uv = f.u.row(row).transpose();
    if (out.norm() < 1e-9) out = uv - mid;
    if (out.norm() < 1e-9) out = Eigen::Vector2d(1, 0);
    const Eigen::Vector3d normal = f.world_dir(out.normalized(), 0.0);
    for (double h = f.h[row] - spacing; h >= 0.5 * spacing; h -= spacing) {
      pts.push_back(f.world(uv, h));
      nrm.push_back(normal);
    }
  }
  starts.push_back(static_cast<Eigen::Index>(pts.size()));
  Shape s;
  s.points.resize(static_cast<Eigen::Index>(pts.size()), 3);
  s.normals.resize(s.points.rows(), 3);
  for (Eigen::Index i = 0; i < s.points.rows(); ++i) {
    s.points.row(i) = pts[static_cast<std::size_t>(i)].transpose();
    s.normals.row(i) = nrm[static_cast<std::size_t>(i)].transpose();
  }
  return s;
}

}  // namespace graspmix::detail
