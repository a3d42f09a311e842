#include "graspmix/perception/surface.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <queue>
#include <stdexcept>
#include <tuple>
#include <unordered_map>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <pcl/features/principal_curvatures.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

namespace graspmix {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

[[noreturn]] void bad(const std::string& m) { throw std::invalid_argument("compute_surface_features: " + m); }

/// The deterministic tangent reference of a normal: world z projected on the tangent plane, or
/// world x where the normal is within acos(0.9) ~ 26 degrees of +-z (there z projects badly).
Eigen::Vector3d tangent_reference(const Eigen::Vector3d& n) {
  const Eigen::Vector3d a = std::abs(n.z()) < 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitX();
  return (a - a.dot(n) * n).normalized();
}

/// The points in a canonical order (by grid cell of side `radius`, then by coordinates) and a hash
/// from cell to its contiguous range. A radius query visits the 27 surrounding cells in a fixed
/// order, so neighbour lists, every sum over them and hence the results are the same for any
/// permutation of the input; and on surfaces it is several times faster than a sorted kd-tree search.
class RadiusGrid {
 public:
  RadiusGrid(const Vec3Array& P, double radius) : r2_(radius * radius) {
    const Eigen::Index N = P.rows();
    const Eigen::Vector3d lo = P.colwise().minCoeff().transpose();
    const Eigen::Vector3d extent = P.colwise().maxCoeff().transpose() - lo;
    if ((extent / radius).maxCoeff() >= static_cast<double>(kCells - 2)) {
      bad("the cloud spans more than 2^21 radii; use a larger radius or crop the cloud");
    }
    std::vector<std::array<std::int64_t, 3>> cell(static_cast<std::size_t>(N));
    for (Eigen::Index i = 0; i < N; ++i)
      for (int k = 0; k < 3; ++k)
        cell[static_cast<std::size_t>(i)][static_cast<std::size_t>(k)] =
            static_cast<std::int64_t>(std::floor((P(i, k) - lo[k]) / radius));
    order_.resize(static_cast<std::size_t>(N));
    for (Eigen::Index i = 0; i < N; ++i) order_[static_cast<std::size_t>(i)] = i;
    std::sort(order_.begin(), order_.end(), [&](Eigen::Index a, Eigen::Index b) {
      const auto& ca = cell[static_cast<std::size_t>(a)];
      const auto& cb = cell[static_cast<std::size_t>(b)];
      if (ca != cb) return ca < cb;
      return std::make_tuple(P(a, 0), P(a, 1), P(a, 2), a) < std::make_tuple(P(b, 0), P(b, 1), P(b, 2), b);
    });
    p_.resize(static_cast<std::size_t>(N));
    cells_.resize(static_cast<std::size_t>(N));
    ranges_.reserve(static_cast<std::size_t>(N));
    for (std::size_t s = 0; s < order_.size(); ++s) {
      p_[s] = P.row(order_[s]).transpose();
      cells_[s] = cell[static_cast<std::size_t>(order_[s])];
      const std::uint64_t key = pack(cells_[s][0], cells_[s][1], cells_[s][2]);
      auto it = ranges_.find(key);
      if (it == ranges_.end()) ranges_.emplace(key, std::make_pair(static_cast<int>(s), static_cast<int>(s) + 1));
      else it->second.second = static_cast<int>(s) + 1;
    }
  }
  int size() const { return static_cast<int>(p_.size()); }
  /// canonical position -> input row
  Eigen::Index row(int i) const { return order_[static_cast<std::size_t>(i)]; }
  const Eigen::Vector3d& point(int i) const { return p_[static_cast<std::size_t>(i)]; }

  /// Every j (itself included) with |p_j - p_i|^2 <= radius^2, in canonical order, with that distance.
  void neighbours(int i, std::vector<int>& nn, std::vector<double>& d2) const {
    nn.clear();
    d2.clear();
    const auto& c = cells_[static_cast<std::size_t>(i)];
    const Eigen::Vector3d& p = point(i);
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          const std::int64_t x = c[0] + dx, y = c[1] + dy, z = c[2] + dz;
          if (x < 0 || y < 0 || z < 0) continue;
          const auto it = ranges_.find(pack(x, y, z));
          if (it == ranges_.end()) continue;
          for (int j = it->second.first; j < it->second.second; ++j) {
            const double d = (p_[static_cast<std::size_t>(j)] - p).squaredNorm();
            if (d <= r2_) {
              nn.push_back(j);
              d2.push_back(d);
            }
          }
        }
  }

 private:
  static constexpr std::int64_t kCells = std::int64_t{1} << 21;
  static std::uint64_t pack(std::int64_t x, std::int64_t y, std::int64_t z) {
    return (static_cast<std::uint64_t>(x) << 42) | (static_cast<std::uint64_t>(y) << 21) | static_cast<std::uint64_t>(z);
  }
  double r2_;
  std::vector<Eigen::Index> order_;
  std::vector<Eigen::Vector3d> p_;
  std::vector<std::array<std::int64_t, 3>> cells_;
  std::unordered_map<std::uint64_t, std::pair<int, int>> ranges_;
};

/// Hoppe-style orientation: each connected part of the k-NN graph is seeded at its point farthest
/// from the cloud's centroid (there the surface is convex and the outward normal points away from
/// the centroid) and oriented along a minimum spanning tree. The edge cost prefers neighbours with
/// parallel normals that lie in each other's tangent planes, so the tree follows the surface and
/// does not jump across thin walls, where neighbours sit along the normal.
void orient_by_propagation(const RadiusGrid& grid, const std::vector<std::vector<int>>& knn, std::vector<Eigen::Vector3d>& n,
                           const std::vector<char>& valid) {
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
    if (n[static_cast<std::size_t>(seed)].dot(grid.point(seed) - centroid) < 0) n[static_cast<std::size_t>(seed)] *= -1.0;
    done[static_cast<std::size_t>(seed)] = 1;
    for (const int j : adj[static_cast<std::size_t>(seed)]) heap.emplace(cost(seed, j), j, seed);
    while (!heap.empty()) {
      const auto [c, i, parent] = heap.top();
      heap.pop();
      if (done[static_cast<std::size_t>(i)]) continue;
      done[static_cast<std::size_t>(i)] = 1;
      if (n[static_cast<std::size_t>(i)].dot(n[static_cast<std::size_t>(parent)]) < 0) n[static_cast<std::size_t>(i)] *= -1.0;
      for (const int j : adj[static_cast<std::size_t>(i)])
        if (!done[static_cast<std::size_t>(j)]) heap.emplace(cost(i, j), j, i);
    }
  }
}

}  // namespace

NormalOrientation normal_orientation_from_string(const std::string& name) {
  if (name == "auto") return NormalOrientation::Auto;
  if (name == "viewpoint") return NormalOrientation::Viewpoint;
  if (name == "propagate") return NormalOrientation::Propagate;
  if (name == "centroid") return NormalOrientation::Centroid;
  if (name == "given") return NormalOrientation::AsGiven;
  throw std::invalid_argument("orientation: unknown rule '" + name +
                              "' (expected auto, viewpoint, propagate, centroid or given)");
}

std::string to_string(NormalOrientation o) {
  switch (o) {
    case NormalOrientation::Auto: return "auto";
    case NormalOrientation::Viewpoint: return "viewpoint";
    case NormalOrientation::Propagate: return "propagate";
    case NormalOrientation::Centroid: return "centroid";
    case NormalOrientation::AsGiven: return "given";
  }
  return "?";
}

PoseArray surface_frames(const Vec3Array& points, const Vec3Array& normals, const Vec3Array& directions,
                         const Eigen::Matrix<bool, Eigen::Dynamic, 1>& isotropic) {
  const Eigen::Index N = points.rows();
  if (normals.rows() != N || directions.rows() != N || isotropic.size() != N) {
    throw std::invalid_argument("surface_frames: points, normals, directions and isotropic need the same rows");
  }
  PoseArray frames(N, 7);
  for (Eigen::Index i = 0; i < N; ++i) {
    const Eigen::Vector3d z = normals.row(i).transpose().normalized();
    const Eigen::Vector3d ref = tangent_reference(z);
    Eigen::Vector3d x = ref;
    if (!isotropic[i]) {
      const Eigen::Vector3d d0 = directions.row(i).transpose();
      Eigen::Vector3d d = d0 - d0.dot(z) * z;
      if (d.norm() > 1e-6) {
        d.normalize();
        // The principal direction has no sign: take the one on the reference's side.
        const double s = d.dot(ref);
        if (s < 0 || (s == 0 && d.dot(z.cross(ref)) < 0)) d = -d;
        x = d;
      }
    }
    Eigen::Matrix3d R;
    R.col(0) = x;
    R.col(1) = z.cross(x);
    R.col(2) = z;
    Eigen::Quaterniond q(R);
    q.normalize();
    if (q.w() < 0) q.coeffs() *= -1.0;
    frames.row(i) << points(i, 0), points(i, 1), points(i, 2), q.x(), q.y(), q.z(), q.w();
  }
  return frames;
}

SurfaceCloud compute_surface_features(const Vec3Array& points, const FeatureSettings& s, const Vec3Array& normals_in,
                                      const Vec3Array& viewpoints) {
  const auto t_start = Clock::now();
  const Eigen::Index N = points.rows();
  if (N == 0) bad("points: the cloud is empty");
  if (N >= std::numeric_limits<int>::max()) bad("points: too many points");
  for (Eigen::Index i = 0; i < N; ++i)
    if (!points.row(i).allFinite()) bad("points: row " + std::to_string(i) + " is not finite (load_cloud drops NaN points)");
  if (!(s.radius > 0) || !std::isfinite(s.radius)) bad("radius must be > 0 (metres), got " + std::to_string(s.radius));
  if (s.min_neighbours < 3) bad("min_neighbours must be >= 3 (a plane needs 3 points)");
  if (s.orientation_neighbours < 1) bad("orientation_neighbours must be >= 1");
  if (!(s.min_anisotropy >= 0) || !(s.flat_curvature >= 0)) bad("min_anisotropy and flat_curvature must be >= 0");
  const bool given = normals_in.rows() > 0;
  if (given && normals_in.rows() != N) {
    bad("normals: " + std::to_string(normals_in.rows()) + " rows for " + std::to_string(N) + " points");
  }
  if (viewpoints.rows() != 0 && viewpoints.rows() != 1 && viewpoints.rows() != N) {
    bad("viewpoints: expected 1 row (one camera) or " + std::to_string(N) + " rows (one per point), got " +
        std::to_string(viewpoints.rows()));
  }
  if (!viewpoints.allFinite()) bad("viewpoints: contains NaN or infinite values");
  if (given) {
    for (Eigen::Index i = 0; i < N; ++i) {
      const Eigen::Vector3d v = normals_in.row(i).transpose();
      if (!v.allFinite() || v.norm() < 1e-12) bad("normals: row " + std::to_string(i) + " is not a finite non-zero vector");
    }
  }
  NormalOrientation rule = s.orientation;
  if (rule == NormalOrientation::Auto) {
    rule = viewpoints.rows() > 0 ? NormalOrientation::Viewpoint
                                 : (given ? NormalOrientation::AsGiven : NormalOrientation::Propagate);
  }
  if (rule == NormalOrientation::Viewpoint && viewpoints.rows() == 0) bad("orientation 'viewpoint' needs viewpoints");
  if (rule == NormalOrientation::AsGiven && !given) bad("orientation 'given' needs normals");
  const int n_threads = s.n_threads > 0 ? s.n_threads : omp_get_max_threads();

  // Everything below works in the grid's canonical order; rows are mapped back at the end.
  const RadiusGrid grid(points, s.radius);
  const int M = grid.size();
  const bool propagate = rule == NormalOrientation::Propagate;
  const int k = s.orientation_neighbours;

  // ---- normals: PCL NormalEstimation's definition (smallest eigenvector of the neighbourhood's
  // covariance within radius), in double about the query point; or the caller's ---------------------
  auto t = Clock::now();
  std::vector<Eigen::Vector3d> n(static_cast<std::size_t>(M), Eigen::Vector3d::Zero());
  std::vector<char> valid(static_cast<std::size_t>(M), 1);
  std::vector<std::vector<int>> knn(propagate ? static_cast<std::size_t>(M) : 0);
#pragma omp parallel num_threads(n_threads)
  {
    std::vector<int> nn;
    std::vector<double> d2;
    std::vector<std::pair<double, int>> near;
#pragma omp for schedule(dynamic, 256)
    for (int i = 0; i < M; ++i) {
      if (given) {
        n[static_cast<std::size_t>(i)] = normals_in.row(grid.row(i)).transpose().normalized();
        if (!propagate) continue;
      }
      grid.neighbours(i, nn, d2);
      if (!given) {
        if (nn.size() < 3) {
          valid[static_cast<std::size_t>(i)] = 0;
          continue;
        }
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
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
        es.computeDirect(C);
        const Eigen::Vector3d v = es.eigenvectors().col(0);
        if (!v.allFinite() || v.norm() < 0.5) {
          valid[static_cast<std::size_t>(i)] = 0;
          continue;
        }
        n[static_cast<std::size_t>(i)] = v.normalized();
      }
      if (propagate) {
        near.clear();
        for (std::size_t a = 0; a < nn.size(); ++a)
          if (nn[a] != i) near.emplace_back(d2[a], nn[a]);
        const std::size_t kk = std::min<std::size_t>(static_cast<std::size_t>(k), near.size());
        std::partial_sort(near.begin(), near.begin() + static_cast<std::ptrdiff_t>(kk), near.end());
        auto& out = knn[static_cast<std::size_t>(i)];
        for (std::size_t a = 0; a < kk; ++a) out.push_back(near[a].second);
      }
    }
  }
  const double t_normals = since(t);

  // ---- outward orientation: before the curvatures, whose projected normals need consistent signs --
  t = Clock::now();
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
  } else if (propagate) {
    orient_by_propagation(grid, knn, n, valid);
  }
  const double t_orient = since(t);

  // ---- principal curvatures: PCL's PrincipalCurvaturesEstimation has no OpenMP variant, so one
  // estimator per thread over the shared grid; points are independent, so threads cannot change results.
  t = Clock::now();
  pcl::PointCloud<pcl::Normal> ncloud;
  ncloud.resize(static_cast<std::size_t>(M));
  for (int i = 0; i < M; ++i) {
    const auto& v = n[static_cast<std::size_t>(i)];
    ncloud[static_cast<std::size_t>(i)] = pcl::Normal(static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z()));
  }
  std::vector<int> count(static_cast<std::size_t>(M), 0);
  std::vector<std::array<double, 5>> pc(static_cast<std::size_t>(M));  // pcx pcy pcz pc1 pc2
  std::vector<char> ok(static_cast<std::size_t>(M), 0);
#pragma omp parallel num_threads(n_threads)
  {
    pcl::PrincipalCurvaturesEstimation<pcl::PointXYZ, pcl::Normal, pcl::PrincipalCurvatures> pce;
    std::vector<int> nn;
    std::vector<double> d2;
    pcl::Indices nn_valid;
#pragma omp for schedule(dynamic, 256)
    for (int i = 0; i < M; ++i) {
      if (!valid[static_cast<std::size_t>(i)]) continue;
      grid.neighbours(i, nn, d2);
      nn_valid.clear();
      for (const int j : nn)
        if (valid[static_cast<std::size_t>(j)]) nn_valid.push_back(static_cast<pcl::index_t>(j));
      count[static_cast<std::size_t>(i)] = static_cast<int>(nn_valid.size());
      if (count[static_cast<std::size_t>(i)] < s.min_neighbours) continue;
      float x, y, z, k1, k2;
      pce.computePointPrincipalCurvatures(ncloud, i, nn_valid, x, y, z, k1, k2);
      // All neighbour normals parallel (a perfect plane): PCL's eigenvector of the zero matrix is NaN
      // while k1 = k2 = 0 is right; the frame rule then picks x.
      if (!(std::isfinite(x) && std::isfinite(y) && std::isfinite(z))) x = y = z = 0.0f;
      pc[static_cast<std::size_t>(i)] = {x, y, z, std::max(k1, 0.0f), std::max(std::min(k2, k1), 0.0f)};
      ok[static_cast<std::size_t>(i)] = std::isfinite(k1) && std::isfinite(k2);
    }
  }
  const double t_curv = since(t);

  // ---- keep the stable points, in input order -----------------------------------------------------
  std::vector<int> pos(static_cast<std::size_t>(N));
  for (int i = 0; i < M; ++i) pos[static_cast<std::size_t>(grid.row(i))] = i;
  std::vector<int> keep;
  for (Eigen::Index r = 0; r < N; ++r)
    if (ok[static_cast<std::size_t>(pos[static_cast<std::size_t>(r)])]) keep.push_back(pos[static_cast<std::size_t>(r)]);
  if (keep.empty()) {
    std::vector<int> c = count;
    std::nth_element(c.begin(), c.begin() + M / 2, c.end());
    bad("no point has a stable neighbourhood: " + std::to_string(s.min_neighbours) + " neighbours within radius " +
        std::to_string(s.radius) + " m are needed, the median point has " + std::to_string(c[static_cast<std::size_t>(M / 2)]) +
        "; use a larger radius or a denser cloud");
  }
  const Eigen::Index K = static_cast<Eigen::Index>(keep.size());
  SurfaceCloud out;
  out.n_input = static_cast<std::size_t>(N);
  out.n_dropped = static_cast<std::size_t>(N - K);
  out.radius = s.radius;
  out.orientation = to_string(rule);
  out.points.resize(K, 3);
  out.normals.resize(K, 3);
  out.curvatures.resize(K, 2);
  out.indices.resize(K);
  out.neighbours.resize(K);
  out.isotropic.resize(K);
  out.frame_ambiguity.resize(K);
  Vec3Array dirs(K, 3);
  for (Eigen::Index r = 0; r < K; ++r) {
    const int i = keep[static_cast<std::size_t>(r)];
    const auto& v = pc[static_cast<std::size_t>(i)];
    out.points.row(r) = points.row(grid.row(i));
    out.normals.row(r) = n[static_cast<std::size_t>(i)].transpose();
    const double k1 = v[3], k2 = v[4];
    out.curvatures.row(r) << k1, k2;
    dirs.row(r) << v[0], v[1], v[2];
    out.indices[r] = static_cast<int>(grid.row(i));
    out.neighbours[r] = count[static_cast<std::size_t>(i)];
    const double anisotropy = (k1 >= s.flat_curvature && k1 > 0) ? (k1 - k2) / k1 : 0.0;  // flat: fully ambiguous
    out.isotropic[r] = k1 < s.flat_curvature || anisotropy < s.min_anisotropy;
    out.frame_ambiguity[r] = M_PI * std::exp(-100.0 * anisotropy * anisotropy);
  }
  out.frames = surface_frames(out.points, out.normals, dirs, out.isotropic);
  out.seconds_normals = t_normals;
  out.seconds_orientation = t_orient;
  out.seconds_curvatures = t_curv;
  out.seconds_total = since(t_start);
  return out;
}

}  // namespace graspmix
