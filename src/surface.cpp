#include "graspmix/surface.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <queue>
#include <stdexcept>
#include <tuple>
#include <vector>

#include <Eigen/Geometry>

#include <pcl/features/normal_3d_omp.h>
#include <pcl/features/principal_curvatures.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>

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

/// Hoppe-style orientation: each connected part of the k-NN graph is seeded at its point farthest
/// from the cloud's centroid (there the surface is convex and the outward normal points away from
/// the centroid) and oriented along a minimum spanning tree. The edge cost prefers neighbours with
/// parallel normals that lie in each other's tangent planes, so the tree follows the surface and
/// does not jump across thin walls, where neighbours sit along the normal.
void orient_by_propagation(const pcl::PointCloud<pcl::PointXYZ>& cloud, const pcl::search::KdTree<pcl::PointXYZ>& tree,
                           std::vector<Eigen::Vector3d>& n, const std::vector<char>& valid, int k, int n_threads) {
  const int N = static_cast<int>(cloud.size());
  std::vector<std::vector<int>> knn(static_cast<std::size_t>(N));
#pragma omp parallel for schedule(dynamic, 256) num_threads(n_threads)
  for (int i = 0; i < N; ++i) {
    if (!valid[static_cast<std::size_t>(i)]) continue;
    pcl::Indices idx;
    std::vector<float> d2;
    tree.nearestKSearch(static_cast<pcl::index_t>(i), k + 1, idx, d2);
    for (const auto j : idx)
      if (j != i && valid[static_cast<std::size_t>(j)]) knn[static_cast<std::size_t>(i)].push_back(static_cast<int>(j));
  }
  std::vector<std::vector<int>> adj(static_cast<std::size_t>(N));
  for (int i = 0; i < N; ++i)
    for (const int j : knn[static_cast<std::size_t>(i)]) {
      adj[static_cast<std::size_t>(i)].push_back(j);
      adj[static_cast<std::size_t>(j)].push_back(i);
    }
  auto P = [&](int i) { return cloud[static_cast<std::size_t>(i)].getVector3fMap().cast<double>(); };
  auto cost = [&](int i, int j) {
    const Eigen::Vector3d& ni = n[static_cast<std::size_t>(i)];
    const Eigen::Vector3d& nj = n[static_cast<std::size_t>(j)];
    Eigen::Vector3d d = P(j) - P(i);
    const double len = d.norm();
    double c = 1.0 - std::abs(ni.dot(nj));
    if (len > 0) c += 0.5 * (std::abs(ni.dot(d)) + std::abs(nj.dot(d))) / len;
    return c;
  };

  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  int n_valid = 0;
  for (int i = 0; i < N; ++i)
    if (valid[static_cast<std::size_t>(i)]) {
      centroid += P(i);
      ++n_valid;
    }
  centroid /= std::max(n_valid, 1);
  // Seeds in order of decreasing distance from the centroid; ties broken by coordinates so that
  // the order of the input does not matter.
  std::vector<int> order;
  for (int i = 0; i < N; ++i)
    if (valid[static_cast<std::size_t>(i)]) order.push_back(i);
  std::vector<double> dist(static_cast<std::size_t>(N), 0.0);
  for (const int i : order) dist[static_cast<std::size_t>(i)] = (P(i) - centroid).squaredNorm();
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    if (dist[static_cast<std::size_t>(a)] != dist[static_cast<std::size_t>(b)])
      return dist[static_cast<std::size_t>(a)] > dist[static_cast<std::size_t>(b)];
    const Eigen::Vector3d pa = P(a), pb = P(b);
    return std::tie(pa.x(), pa.y(), pa.z()) < std::tie(pb.x(), pb.y(), pb.z());
  });

  std::vector<char> done(static_cast<std::size_t>(N), 0);
  using Item = std::tuple<double, int, int>;  // cost, node, parent
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
  for (const int seed : order) {
    if (done[static_cast<std::size_t>(seed)]) continue;
    if (n[static_cast<std::size_t>(seed)].dot(P(seed) - centroid) < 0) n[static_cast<std::size_t>(seed)] *= -1.0;
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
  NormalOrientation rule = s.orientation;
  if (rule == NormalOrientation::Auto) {
    rule = viewpoints.rows() > 0 ? NormalOrientation::Viewpoint
                                 : (given ? NormalOrientation::AsGiven : NormalOrientation::Propagate);
  }
  if (rule == NormalOrientation::Viewpoint && viewpoints.rows() == 0) bad("orientation 'viewpoint' needs viewpoints");
  if (rule == NormalOrientation::AsGiven && !given) bad("orientation 'given' needs normals");
  const int n_threads = s.n_threads > 0 ? s.n_threads : omp_get_max_threads();

  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud(new pcl::PointCloud<pcl::PointXYZ>);
  cloud->resize(static_cast<std::size_t>(N));
  for (Eigen::Index i = 0; i < N; ++i) {
    (*cloud)[static_cast<std::size_t>(i)] =
        pcl::PointXYZ(static_cast<float>(points(i, 0)), static_cast<float>(points(i, 1)), static_cast<float>(points(i, 2)));
  }
  pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);
  tree->setInputCloud(cloud);

  // ---- normals (PCL's NormalEstimationOMP, or the caller's) --------------------------------------
  auto t = Clock::now();
  std::vector<Eigen::Vector3d> n(static_cast<std::size_t>(N));
  std::vector<char> valid(static_cast<std::size_t>(N), 1);
  if (given) {
    for (Eigen::Index i = 0; i < N; ++i) {
      const Eigen::Vector3d v = normals_in.row(i).transpose();
      if (!v.allFinite() || v.norm() < 1e-12) bad("normals: row " + std::to_string(i) + " is not a finite non-zero vector");
      n[static_cast<std::size_t>(i)] = v.normalized();
    }
  } else {
    pcl::NormalEstimationOMP<pcl::PointXYZ, pcl::Normal> ne(static_cast<unsigned>(n_threads));
    ne.setInputCloud(cloud);
    ne.setSearchMethod(tree);
    ne.setRadiusSearch(s.radius);
    pcl::PointCloud<pcl::Normal> est;
    ne.compute(est);
    for (Eigen::Index i = 0; i < N; ++i) {
      const auto& e = est[static_cast<std::size_t>(i)];
      const Eigen::Vector3d v(e.normal_x, e.normal_y, e.normal_z);
      valid[static_cast<std::size_t>(i)] = v.allFinite() && v.norm() > 0.5;
      n[static_cast<std::size_t>(i)] = valid[static_cast<std::size_t>(i)] ? v.normalized() : Eigen::Vector3d::Zero();
    }
  }
  const double t_normals = since(t);

  // ---- outward orientation: before the curvatures, whose projected normals need consistent signs --
  t = Clock::now();
  if (rule == NormalOrientation::Viewpoint) {
    for (Eigen::Index i = 0; i < N; ++i) {
      const Eigen::Vector3d v = viewpoints.row(viewpoints.rows() == 1 ? 0 : i).transpose();
      if (n[static_cast<std::size_t>(i)].dot(v - points.row(i).transpose()) < 0) n[static_cast<std::size_t>(i)] *= -1.0;
    }
  } else if (rule == NormalOrientation::Centroid) {
    const Eigen::Vector3d c = points.colwise().mean().transpose();
    for (Eigen::Index i = 0; i < N; ++i)
      if (n[static_cast<std::size_t>(i)].dot(points.row(i).transpose() - c) < 0) n[static_cast<std::size_t>(i)] *= -1.0;
  } else if (rule == NormalOrientation::Propagate) {
    orient_by_propagation(*cloud, *tree, n, valid, s.orientation_neighbours, n_threads);
  }
  const double t_orient = since(t);

  // ---- principal curvatures: PCL's estimator has no OpenMP variant, so one estimator per thread
  // on the shared kd-tree; every point is independent, so the thread count cannot change results.
  t = Clock::now();
  pcl::PointCloud<pcl::Normal> ncloud;
  ncloud.resize(static_cast<std::size_t>(N));
  for (Eigen::Index i = 0; i < N; ++i) {
    const auto& v = n[static_cast<std::size_t>(i)];
    ncloud[static_cast<std::size_t>(i)] = pcl::Normal(static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z()));
  }
  Eigen::VectorXi count = Eigen::VectorXi::Zero(N);
  Eigen::Matrix<double, Eigen::Dynamic, 5, Eigen::RowMajor> pc(N, 5);  // pcx pcy pcz pc1 pc2
  std::vector<char> ok(static_cast<std::size_t>(N), 0);
#pragma omp parallel num_threads(n_threads)
  {
    pcl::PrincipalCurvaturesEstimation<pcl::PointXYZ, pcl::Normal, pcl::PrincipalCurvatures> pce;
    pcl::Indices nn, nn_valid;
    std::vector<float> d2;
#pragma omp for schedule(dynamic, 128)
    for (Eigen::Index i = 0; i < N; ++i) {
      if (!valid[static_cast<std::size_t>(i)]) continue;
      tree->radiusSearch(static_cast<pcl::index_t>(i), s.radius, nn, d2);
      nn_valid.clear();
      for (const auto j : nn)
        if (valid[static_cast<std::size_t>(j)]) nn_valid.push_back(j);
      count[i] = static_cast<int>(nn_valid.size());
      if (count[i] < s.min_neighbours) continue;
      float x, y, z, k1, k2;
      pce.computePointPrincipalCurvatures(ncloud, static_cast<int>(i), nn_valid, x, y, z, k1, k2);
      // All neighbour normals parallel (a perfect plane): PCL's eigenvector of the zero matrix is NaN
      // while k1 = k2 = 0 is right; the frame rule then picks x.
      if (!(std::isfinite(x) && std::isfinite(y) && std::isfinite(z))) x = y = z = 0.0f;
      pc.row(i) << x, y, z, std::max(k1, 0.0f), std::max(std::min(k2, k1), 0.0f);
      ok[static_cast<std::size_t>(i)] = pc.row(i).allFinite();
    }
  }
  const double t_curv = since(t);

  // ---- keep the stable points ------------------------------------------------------------------
  std::vector<Eigen::Index> keep;
  for (Eigen::Index i = 0; i < N; ++i)
    if (ok[static_cast<std::size_t>(i)]) keep.push_back(i);
  if (keep.empty()) {
    std::vector<int> c(count.data(), count.data() + N);
    std::nth_element(c.begin(), c.begin() + N / 2, c.end());
    bad("no point has a stable neighbourhood: " + std::to_string(s.min_neighbours) + " neighbours within radius " +
        std::to_string(s.radius) + " m are needed, the median point has " + std::to_string(c[static_cast<std::size_t>(N / 2)]) +
        "; use a larger radius or a denser cloud");
  }
  const Eigen::Index M = static_cast<Eigen::Index>(keep.size());
  SurfaceCloud out;
  out.n_input = static_cast<std::size_t>(N);
  out.n_dropped = static_cast<std::size_t>(N - M);
  out.radius = s.radius;
  out.orientation = to_string(rule);
  out.points.resize(M, 3);
  out.normals.resize(M, 3);
  out.curvatures.resize(M, 2);
  out.indices.resize(M);
  out.neighbours.resize(M);
  out.isotropic.resize(M);
  out.frame_ambiguity.resize(M);
  Vec3Array dirs(M, 3);
  for (Eigen::Index r = 0; r < M; ++r) {
    const Eigen::Index i = keep[static_cast<std::size_t>(r)];
    out.points.row(r) = points.row(i);
    out.normals.row(r) = n[static_cast<std::size_t>(i)].transpose();
    const double k1 = pc(i, 3), k2 = pc(i, 4);
    out.curvatures.row(r) << k1, k2;
    dirs.row(r) = pc.row(i).head<3>();
    out.indices[r] = static_cast<int>(i);
    out.neighbours[r] = count[i];
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
