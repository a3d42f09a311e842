#include "surface_normals.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <queue>
#include <tuple>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>

namespace graspmix::surface_detail {

namespace {

/// Hoppe-style orientation: each connected part of the k-NN graph is seeded at its point farthest
/// from the cloud's centroid (there the surface is convex and the outward normal points away from
/// the centroid) and oriented along a minimum spanning tree. The edge cost prefers neighbours with
/// parallel normals that lie in each other's tangent planes, so the tree follows the surface and
/// does not jump across thin walls, where neighbours sit along the normal.
void orient_by_propagation(const RadiusGrid& grid, const std::vector<std::vector<int>>& knn,
                           std::vector<Eigen::Vector3d>& n, const std::vector<char>& valid) {
  const int N = grid.size();
  std::vector<std::vector<int>> adj(static_cast<std::size_t>(N));
  for (int i = 0; i < N; ++i)
    for (const int j : knn[static_cast<std::size_t>(i)]) {
      if (!valid[static_cast<std::size_t>(i)] || !valid[static_cast<std::size_t>(j)]) continue;
      adj[static_cast<std::size_t>(i)].push_back(j);
      adj[static_cast<std::size_t>(j)].push_back(i);
    }
  auto cost = [&](int i, int j) {
    const Eigen::Vector3d& ni = n[static_cast<std::size_t>(i)];
    const Eigen::Vector3d& nj = n[static_cast<std::size_t>(j)];
    const Eigen::Vector3d d = grid.point(j) - grid.point(i);
    const double len = d.norm();
    double c = 1.0 - std::abs(ni.dot(nj));
    if (len > 0) c += 0.5 * (std::abs(ni.dot(d)) + std::abs(nj.dot(d))) / len;
    return c;
  };
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  int n_valid = 0;
  for (int i = 0; i < N; ++i)
    if (valid[static_cast<std::size_t>(i)]) {
      centroid += grid.point(i);
      ++n_valid;
    }
  centroid /= std::max(n_valid, 1);
  std::vector<int> seeds;
  for (int i = 0; i < N; ++i)
    if (valid[static_cast<std::size_t>(i)]) seeds.push_back(i);
  std::vector<double> dist(static_cast<std::size_t>(N), 0.0);
  for (const int i : seeds) dist[static_cast<std::size_t>(i)] = (grid.point(i) - centroid).squaredNorm();
  // Farthest first; equal distances keep the canonical order (stable sort).
  std::stable_sort(seeds.begin(), seeds.end(),
                   [&](int a, int b) { return dist[static_cast<std::size_t>(a)] > dist[static_cast<std::size_t>(b)]; });
  std::vector<char> done(static_cast<std::size_t>(N), 0);
  using Item = std::tuple<double, int, int>;  // cost, node, parent
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
  for (const int seed : seeds) {
    if (done[static_cast<std::size_t>(seed)]) continue;
    if (n[static_cast<std::size_t>(seed)].dot(grid.point(seed) - centroid) < 0)
      n[static_cast<std::size_t>(seed)] *= -1.0;
    done[static_cast<std::size_t>(seed)] = 1;
    for (const int j : adj[static_cast<std::size_t>(seed)]) heap.emplace(cost(seed, j), j, seed);
    while (!heap.empty()) {
      const auto [c, i, parent] = heap.top();
      heap.pop();
      if (done[static_cast<std::size_t>(i)]) continue;
      done[static_cast<std::size_t>(i)] = 1;
      if (n[static_cast<std::size_t>(i)].dot(n[static_cast<std::size_t>(parent)]) < 0)
        n[static_cast<std::size_t>(i)] *= -1.0;
      for (const int j : adj[static_cast<std::size_t>(i)])
        if (!done[static_cast<std::size_t>(j)]) heap.emplace(cost(i, j), j, i);
    }
  }
}

/// PCL NormalEstimation's definition: the smallest eigenvector of the neighbourhood's covariance,
/// in double about the query point; zero where it is undetermined, including a neighbourhood whose
/// points coincide or lie on one line (there every direction across the line would do: PCL returns
/// an arbitrary one).
Eigen::Vector3d pca_normal(const RadiusGrid& grid, int i, const std::vector<int>& nn, char& degenerate) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
  for (const int j : nn) {
    const Eigen::Vector3d d = grid.point(j) - grid.point(i);
    mean += d;
    C.noalias() += d * d.transpose();
  }
  const double inv = 1.0 / static_cast<double>(nn.size());
  mean *= inv;
  C = C * inv - mean * mean.transpose();
  // Coincident or collinear points: the covariance has rank < 2, i.e. the sum of its principal 2 x 2
  // minors (lambda0 lambda1 + lambda0 lambda2 + lambda1 lambda2) vanishes against trace^2. Read from C
  // itself: computeDirect's eigenvalues are not accurate enough near repeated zeros.
  const double minors = C(0, 0) * C(1, 1) - C(0, 1) * C(0, 1) + C(0, 0) * C(2, 2) - C(0, 2) * C(0, 2) +
                        C(1, 1) * C(2, 2) - C(1, 2) * C(1, 2);
  const double trace = C.trace();
  degenerate = !(minors > 1e-10 * trace * trace);
  if (degenerate) return Eigen::Vector3d::Zero();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
  es.computeDirect(C);
  const Eigen::Vector3d v = es.eigenvectors().col(0);
  if (!v.allFinite() || v.norm() < 0.5) return Eigen::Vector3d::Zero();
  return v.normalized();
}

/// The k nearest of the neighbours nn (squared distances d2) of i, itself excluded, nearest first.
void nearest(int i, const std::vector<int>& nn, const std::vector<double>& d2, int k,
             std::vector<std::pair<double, int>>& near, std::vector<int>& out) {
  near.clear();
  for (std::size_t a = 0; a < nn.size(); ++a)
    if (nn[a] != i) near.emplace_back(d2[a], nn[a]);
  const std::size_t kk = std::min<std::size_t>(static_cast<std::size_t>(k), near.size());
  std::partial_sort(near.begin(), near.begin() + static_cast<std::ptrdiff_t>(kk), near.end());
  for (std::size_t a = 0; a < kk; ++a) out.push_back(near[a].second);
}

}  // namespace

/// The caller's normals or estimated ones, and the k-NN graph when the orientation propagates.
Normals estimate_normals(const RadiusGrid& grid, const SurfaceFeatureSettings& s, const Vec3Array& normals_in,
                         bool propagate, int n_threads) {
  const int M = grid.size();
  const bool given = normals_in.rows() > 0;
  const double r2 = s.radius * s.radius;
  Normals out;
  out.n.assign(static_cast<std::size_t>(M), Eigen::Vector3d::Zero());
  out.valid.assign(static_cast<std::size_t>(M), 1);
  out.degenerate.assign(static_cast<std::size_t>(M), 0);
  out.knn.resize(propagate ? static_cast<std::size_t>(M) : 0);
  NeighbourCap cap(s);
#pragma omp parallel num_threads(n_threads)
  {
    std::vector<int> nn;
    std::vector<double> d2;
    std::vector<std::pair<double, int>> near;
#pragma omp for schedule(dynamic, 256)
    for (int i = 0; i < M; ++i) {
      if (cap.hit()) continue;
      if (given) {
        out.n[static_cast<std::size_t>(i)] = normals_in.row(grid.row(i)).transpose().normalized();
        if (!propagate) continue;
      }
      grid.neighbours(i, r2, nn, d2);
      if (cap.over(nn.size())) continue;
      if (!given) {
        if (nn.size() < 3) {
          out.valid[static_cast<std::size_t>(i)] = 0;
          continue;
        }
        const Eigen::Vector3d v = pca_normal(grid, i, nn, out.degenerate[static_cast<std::size_t>(i)]);
        if (v.isZero(0.0)) {
          out.valid[static_cast<std::size_t>(i)] = 0;
          continue;
        }
        out.n[static_cast<std::size_t>(i)] = v;
      }
      if (propagate) nearest(i, nn, d2, s.orientation_neighbours, near, out.knn[static_cast<std::size_t>(i)]);
    }
  }
  cap.throw_if_hit();
  return out;
}

/// Outward orientation by the rule: before the curvatures, whose projected normals need consistent signs.
void orient_normals(NormalOrientation rule, const RadiusGrid& grid, const Vec3Array& viewpoints, Normals& normals) {
  const int M = grid.size();
  std::vector<Eigen::Vector3d>& n = normals.n;
  if (rule == NormalOrientation::Viewpoint) {
    for (int i = 0; i < M; ++i) {
      const Eigen::Vector3d v = viewpoints.row(viewpoints.rows() == 1 ? 0 : grid.row(i)).transpose();
      if (n[static_cast<std::size_t>(i)].dot(v - grid.point(i)) < 0) n[static_cast<std::size_t>(i)] *= -1.0;
    }
  } else if (rule == NormalOrientation::Centroid) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (int i = 0; i < M; ++i) c += grid.point(i);
    c /= M;
    for (int i = 0; i < M; ++i)
      if (n[static_cast<std::size_t>(i)].dot(grid.point(i) - c) < 0) n[static_cast<std::size_t>(i)] *= -1.0;
  } else if (rule == NormalOrientation::Propagate) {
    orient_by_propagation(grid, normals.knn, n, normals.valid);
  }
}

}  // namespace graspmix::surface_detail
