#include "graspmix/perception/surface.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <queue>
#include <stdexcept>
#include <tuple>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <pcl/features/principal_curvatures.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "graspmix/core/frame_jitter.hpp"
#include "surface_normals.hpp"

namespace graspmix {

namespace {

using namespace surface_detail;
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

/// The deterministic tangent reference of a normal: world z projected on the tangent plane, or
/// world x where the normal is within acos(0.9) ~ 26 degrees of +-z (there z projects badly).
Eigen::Vector3d tangent_reference(const Eigen::Vector3d& n) {
  const Eigen::Vector3d a = std::abs(n.z()) < 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitX();
  return (a - a.dot(n) * n).normalized();
}

/// The inputs of compute_surface_features checked, and the orientation rule that applies (Auto resolved).
NormalOrientation check_inputs(const Vec3Array& points, const SurfaceFeatureSettings& s, const Vec3Array& normals_in,
                               const Vec3Array& viewpoints) {
  const Eigen::Index N = points.rows();
  if (N == 0) bad("points: the cloud is empty");
  if (N >= std::numeric_limits<int>::max()) bad("points: too many points");
  for (Eigen::Index i = 0; i < N; ++i)
    if (!points.row(i).allFinite())
      bad("points: row " + std::to_string(i) + " is not finite (load_cloud drops NaN points)");
  if (!(s.radius > 0) || !std::isfinite(s.radius)) bad("radius must be > 0 (metres), got " + std::to_string(s.radius));
  if (s.min_neighbours < 3) bad("min_neighbours must be >= 3 (a plane needs 3 points)");
  if (s.orientation_neighbours < 1) bad("orientation_neighbours must be >= 1");
  if (s.n_threads < 0 || s.n_threads > kMaxFeatureThreads) {
    bad("n_threads must be 0 (OpenMP's default) or 1.." + std::to_string(kMaxFeatureThreads) + ", got " +
        std::to_string(s.n_threads));
  }
  if (s.max_neighbours < 0 || (s.max_neighbours > 0 && s.max_neighbours < s.min_neighbours)) {
    bad("max_neighbours must be 0 (no cap) or >= min_neighbours (" + std::to_string(s.min_neighbours) + "), got " +
        std::to_string(s.max_neighbours));
  }
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
      if (!v.allFinite() || v.norm() < 1e-12)
        bad("normals: row " + std::to_string(i) + " is not a finite non-zero vector");
    }
  }
  NormalOrientation rule = s.orientation;
  if (rule == NormalOrientation::Auto) {
    rule = viewpoints.rows() > 0 ? NormalOrientation::Viewpoint
                                 : (given ? NormalOrientation::AsGiven : NormalOrientation::Propagate);
  }
  if (rule == NormalOrientation::Viewpoint && viewpoints.rows() == 0) bad("orientation 'viewpoint' needs viewpoints");
  if (rule == NormalOrientation::AsGiven && !given) bad("orientation 'given' needs normals");
  return rule;
}

/// The grid over the points whose cells are one radius wide: the radius search of every stage below.
RadiusGrid radius_grid(const Vec3Array& points, double radius) {
  const Eigen::Vector3d lo = points.colwise().minCoeff().transpose();
  const Eigen::Vector3d extent = points.colwise().maxCoeff().transpose() - lo;
  if (extent.maxCoeff() == 0) {
    bad("points: all " + std::to_string(points.rows()) + " points coincide (zero extent): no surface to describe");
  }
  if ((extent / radius).maxCoeff() >= static_cast<double>(RadiusGrid::kMaxCells - 2)) {
    bad("the cloud spans more than 2^21 radii; use a larger radius or crop the cloud");
  }
  const std::int64_t n = RadiusGrid::kMaxCells;
  return RadiusGrid(points, lo, radius, {n, n, n}, RadiusGrid::Layout::Sparse);
}

/// Principal curvatures in canonical order: neighbour counts, [pcx pcy pcz pc1 pc2] and which are finite.
struct Curvatures {
  std::vector<int> count;
  std::vector<char> degenerate;  ///< every neighbour coincides with the point (zero extent)
  std::vector<std::array<double, 5>> pc;
  std::vector<char> ok;
};

/// PCL's PrincipalCurvaturesEstimation has no OpenMP variant, so one estimator per thread over the shared
/// grid; points are independent, so threads cannot change results.
Curvatures principal_curvatures(const RadiusGrid& grid, const Normals& normals, const SurfaceFeatureSettings& s,
                                int n_threads) {
  const int M = grid.size();
  const double r2 = s.radius * s.radius;
  pcl::PointCloud<pcl::Normal> ncloud;
  ncloud.resize(static_cast<std::size_t>(M));
  for (int i = 0; i < M; ++i) {
    const auto& v = normals.n[static_cast<std::size_t>(i)];
    ncloud[static_cast<std::size_t>(i)] =
        pcl::Normal(static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z()));
  }
  const std::vector<char>& valid = normals.valid;
  Curvatures out;
  out.count.assign(static_cast<std::size_t>(M), 0);
  out.pc.resize(static_cast<std::size_t>(M));
  out.ok.assign(static_cast<std::size_t>(M), 0);
  out.degenerate.assign(static_cast<std::size_t>(M), 0);
  NeighbourCap cap(s);
#pragma omp parallel num_threads(n_threads)
  {
    pcl::PrincipalCurvaturesEstimation<pcl::PointXYZ, pcl::Normal, pcl::PrincipalCurvatures> pce;
    std::vector<int> nn;
    std::vector<double> d2;
    pcl::Indices nn_valid;
#pragma omp for schedule(dynamic, 256)
    for (int i = 0; i < M; ++i) {
      if (!valid[static_cast<std::size_t>(i)] || cap.hit()) continue;
      grid.neighbours(i, r2, nn, d2);
      if (cap.over(nn.size())) continue;
      // Every neighbour at the point itself (duplicates, with given normals): no surface around it.
      if (std::all_of(d2.begin(), d2.end(), [](double d) { return d == 0; })) {
        out.degenerate[static_cast<std::size_t>(i)] = 1;
        continue;
      }
      nn_valid.clear();
      for (const int j : nn)
        if (valid[static_cast<std::size_t>(j)]) nn_valid.push_back(static_cast<pcl::index_t>(j));
      out.count[static_cast<std::size_t>(i)] = static_cast<int>(nn_valid.size());
      if (out.count[static_cast<std::size_t>(i)] < s.min_neighbours) continue;
      float x, y, z, k1, k2;
      pce.computePointPrincipalCurvatures(ncloud, i, nn_valid, x, y, z, k1, k2);
      // All neighbour normals parallel (a perfect plane): PCL's eigenvector of the zero matrix is NaN
      // while k1 = k2 = 0 is right; the frame rule then picks x.
      if (!(std::isfinite(x) && std::isfinite(y) && std::isfinite(z))) x = y = z = 0.0f;
      out.pc[static_cast<std::size_t>(i)] = {x, y, z, std::max(k1, 0.0f), std::max(std::min(k2, k1), 0.0f)};
      out.ok[static_cast<std::size_t>(i)] = std::isfinite(k1) && std::isfinite(k2);
    }
  }
  cap.throw_if_hit();
  return out;
}

/// The canonical positions of the stable points, in input order; throws if there is none.
std::vector<int> stable_points(const RadiusGrid& grid, const Normals& normals, const Curvatures& curv,
                               const SurfaceFeatureSettings& s) {
  const int M = grid.size();
  std::vector<int> pos(static_cast<std::size_t>(M));
  for (int i = 0; i < M; ++i) pos[static_cast<std::size_t>(grid.row(i))] = i;
  std::vector<int> keep;
  for (int r = 0; r < M; ++r)
    if (curv.ok[static_cast<std::size_t>(pos[static_cast<std::size_t>(r)])])
      keep.push_back(pos[static_cast<std::size_t>(r)]);
  if (keep.empty()) {
    int degenerate = 0;
    for (int i = 0; i < M; ++i) {
      degenerate += normals.degenerate[static_cast<std::size_t>(i)] || curv.degenerate[static_cast<std::size_t>(i)];
    }
    if (degenerate == M) {
      bad("degenerate input: the neighbourhood of every point (" + std::to_string(M) +
          ") has its points coinciding or on one line, so no surface is defined (duplicated points?)");
    }
    std::vector<int> c = curv.count;
    std::nth_element(c.begin(), c.begin() + M / 2, c.end());
    bad("no point has a stable neighbourhood: " + std::to_string(s.min_neighbours) + " neighbours within radius " +
        std::to_string(s.radius) + " m are needed, the median point has " +
        std::to_string(c[static_cast<std::size_t>(M / 2)]) + "; use a larger radius or a denser cloud");
  }
  return keep;
}

/// The kept points' rows of the SurfaceCloud, frames included.
SurfaceCloud assemble(const Vec3Array& points, const RadiusGrid& grid, const Normals& normals, const Curvatures& curv,
                      const std::vector<int>& keep, const SurfaceFeatureSettings& s) {
  const Eigen::Index K = static_cast<Eigen::Index>(keep.size());
  SurfaceCloud out;
  out.n_input = static_cast<std::size_t>(points.rows());
  out.n_dropped = static_cast<std::size_t>(points.rows() - K);
  out.radius = s.radius;
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
    const auto& v = curv.pc[static_cast<std::size_t>(i)];
    out.points.row(r) = points.row(grid.row(i));
    out.normals.row(r) = normals.n[static_cast<std::size_t>(i)].transpose();
    const double k1 = v[3], k2 = v[4];
    out.curvatures.row(r) << k1, k2;
    dirs.row(r) << v[0], v[1], v[2];
    out.indices[r] = static_cast<int>(grid.row(i));
    out.neighbours[r] = curv.count[static_cast<std::size_t>(i)];
    const double anisotropy = (k1 >= s.flat_curvature && k1 > 0) ? (k1 - k2) / k1 : 0.0;  // flat: fully ambiguous
    out.isotropic[r] = k1 < s.flat_curvature || anisotropy < s.min_anisotropy;
    out.frame_ambiguity[r] = frame_jitter_angle(anisotropy, kKopickiJitterSharpness);
  }
  out.frames = surface_frames(out.points, out.normals, dirs, out.isotropic);
  return out;
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
    case NormalOrientation::Auto:
      return "auto";
    case NormalOrientation::Viewpoint:
      return "viewpoint";
    case NormalOrientation::Propagate:
      return "propagate";
    case NormalOrientation::Centroid:
      return "centroid";
    case NormalOrientation::AsGiven:
      return "given";
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

SurfaceCloud compute_surface_features(const Vec3Array& points, const SurfaceFeatureSettings& s,
                                      const Vec3Array& normals_in, const Vec3Array& viewpoints) {
  const auto t_start = Clock::now();
  const NormalOrientation rule = check_inputs(points, s, normals_in, viewpoints);
  const int n_threads = s.n_threads > 0 ? s.n_threads : omp_get_max_threads();
  // Everything below works in the grid's canonical order; rows are mapped back at the end.
  const RadiusGrid grid = radius_grid(points, s.radius);

  auto t = Clock::now();
  Normals normals = estimate_normals(grid, s, normals_in, rule == NormalOrientation::Propagate, n_threads);
  const double t_normals = since(t);
  t = Clock::now();
  orient_normals(rule, grid, viewpoints, normals);
  const double t_orient = since(t);
  t = Clock::now();
  const Curvatures curv = principal_curvatures(grid, normals, s, n_threads);
  const double t_curv = since(t);

  SurfaceCloud out = assemble(points, grid, normals, curv, stable_points(grid, normals, curv, s), s);
  out.orientation = to_string(rule);
  out.seconds_normals = t_normals;
  out.seconds_orientation = t_orient;
  out.seconds_curvatures = t_curv;
  out.seconds_total = since(t_start);
  return out;
}

}  // namespace graspmix
