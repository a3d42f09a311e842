#include "cloud_filters.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <utility>

#include <pcl/console/print.h>
#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/sample_consensus/ransac.h>
#include <pcl/sample_consensus/sac_model_plane.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/extract_clusters.h>
#include <boost/sort/spreadsort/integer_sort.hpp>

#include "core/uniform_grid.hpp"
#include "flann_distance.hpp"
#include "knn_distances.hpp"

namespace graspmix::detail {

namespace {

/// PCL's SAC classes seed their generators with 12345 (or the clock); these reseed them from the
/// caller's seed so that RANSAC is both deterministic and under the caller's control.
class SeededStockPlaneModel : public pcl::SampleConsensusModelPlane<pcl::PointXYZ> {
 public:
  SeededStockPlaneModel(const Cloud::ConstPtr& cloud, unsigned seed)
      : pcl::SampleConsensusModelPlane<pcl::PointXYZ>(cloud) {
    rng_alg_.seed(seed);
  }
};

class SeededPlaneModel : public SeededStockPlaneModel {
 public:
  using SeededStockPlaneModel::SeededStockPlaneModel;

  // PCL's count and selection (countWithinDistanceStandard, selectWithinDistance: |coeffs . (p, 1)| <
  // threshold) with the dot product written out as the one PCL's build computes, Eigen's SSE reduction
  // (c0 x + c2 z) + (c1 y + c3), so the same points pass, at a fraction of the cost of a dynamic-size
  // dot product per point: RANSAC scores every hypothesis on every point.
  std::size_t countWithinDistance(const Eigen::VectorXf& coeffs, const double threshold) const override {
    if (!isModelValid(coeffs)) return 0;
    const float c0 = coeffs[0], c1 = coeffs[1], c2 = coeffs[2], c3 = coeffs[3];
    std::size_t nr_p = 0;
    for (const auto row : *indices_) {
      const auto& p = (*input_)[static_cast<std::size_t>(row)];
      nr_p += std::abs((c0 * p.x + c2 * p.z) + (c1 * p.y + c3)) < threshold;
    }
    return nr_p;
  }

  void selectWithinDistance(const Eigen::VectorXf& coeffs, const double threshold, pcl::Indices& inliers) override {
    if (!isModelValid(coeffs)) return;
    inliers.clear();
    error_sqr_dists_.clear();
    inliers.reserve(indices_->size());
    error_sqr_dists_.reserve(indices_->size());
    const float c0 = coeffs[0], c1 = coeffs[1], c2 = coeffs[2], c3 = coeffs[3];
    for (const auto row : *indices_) {
      const auto& p = (*input_)[static_cast<std::size_t>(row)];
      const float distance = std::abs((c0 * p.x + c2 * p.z) + (c1 * p.y + c3));
      if (distance < threshold) {
        inliers.push_back(row);
        error_sqr_dists_.push_back(static_cast<double>(distance));
      }
    }
  }
};

class SeededRansac : public pcl::RandomSampleConsensus<pcl::PointXYZ> {
 public:
  SeededRansac(const pcl::SampleConsensusModel<pcl::PointXYZ>::Ptr& model, double threshold, unsigned seed)
      : pcl::RandomSampleConsensus<pcl::PointXYZ>(model, threshold) {
    rng_->base().seed(seed);
    threads_ = -1;  // PCL's parallel RANSAC races on the best model: results would depend on timing
  }
};

unsigned fold_seed(std::uint64_t s) { return static_cast<unsigned>((s ^ (s >> 32)) & 0xffffffffu); }

/// pcl::VoxelGrid's (cell index, row) pair: the same layout and order, so the same sort gives the same order.
struct CellRow {
  unsigned int idx;
  unsigned int row;
  bool operator<(const CellRow& o) const { return idx < o.idx; }
};

int find_root(std::vector<int>& parent, int i) {
  while (parent[static_cast<std::size_t>(i)] != i) {
    const int up = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    parent[static_cast<std::size_t>(i)] = up;
    i = up;
  }
  return i;
}

std::vector<std::vector<int>> pcl_clusters(const Cloud::ConstPtr& cloud, double tolerance) {
  pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);
  pcl::EuclideanClusterExtraction<pcl::PointXYZ> ec;
  ec.setClusterTolerance(tolerance);
  ec.setMinClusterSize(1);
  ec.setMaxClusterSize(std::numeric_limits<int>::max());
  ec.setSearchMethod(tree);
  ec.setInputCloud(cloud);
  std::vector<pcl::PointIndices> found;
  ec.extract(found);
  std::vector<std::vector<int>> out;
  for (const auto& f : found) {
    out.emplace_back(f.indices.begin(), f.indices.end());
    std::sort(out.back().begin(), out.back().end());
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.front() < b.front(); });
  return out;
}

}  // namespace

namespace {

/// A uniform grid over the cloud whose 27 cells around a point's hold every point within `tolerance` of it by
/// FLANN's float test (cells a little wider than the tolerance); none when the cloud spans too many cells or has a
/// non-finite point.
std::optional<UniformGrid> tolerance_grid(const Cloud& cloud, double tolerance) {
  const auto n = static_cast<Eigen::Index>(cloud.size());
  for (const auto& p : cloud)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return std::nullopt;
  Vec3Array P(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) P.row(i) = cloud[static_cast<std::size_t>(i)].getVector3fMap().cast<double>();
  const double h = tolerance * 1.001;
  const Eigen::Vector3d lo = P.colwise().minCoeff().transpose(), hi = P.colwise().maxCoeff().transpose();
  UniformGrid::Cell dims;
  double n_cells = 1;
  for (int k = 0; k < 3; ++k) {
    const double d = std::floor((hi[k] - lo[k]) / h) + 1;
    if (d > static_cast<double>(UniformGrid::kMaxCells)) return std::nullopt;
    dims[static_cast<std::size_t>(k)] = static_cast<std::int64_t>(d);
    n_cells *= d;
  }
  const auto layout =
      n_cells <= 8.0 * static_cast<double>(n) + 1e4 ? UniformGrid::Layout::Dense : UniformGrid::Layout::Sparse;
  return std::optional<UniformGrid>(std::in_place, P, lo, h, dims, layout);
}

/// The 27 cells around cell c, clipped to the grid.
std::pair<UniformGrid::Cell, UniformGrid::Cell> cells_around(const UniformGrid& grid, const UniformGrid::Cell& c) {
  UniformGrid::Cell c0, c1;
  for (std::size_t k = 0; k < 3; ++k) {
    c0[k] = std::max<std::int64_t>(c[k] - 1, 0);
    c1[k] = std::min<std::int64_t>(c[k] + 1, grid.dims()[k] - 1);
  }
  return {c0, c1};
}

}  // namespace

struct RadiusSearch::Impl {
  Cloud::ConstPtr cloud;
  double radius = 0;
  std::optional<UniformGrid> grid;
  std::vector<int> slot;  ///< per row its canonical position in the grid
  pcl::KdTreeFLANN<pcl::PointXYZ> tree;
};

RadiusSearch::RadiusSearch(const Cloud::ConstPtr& cloud, double radius) : impl_(std::make_unique<Impl>()) {
  impl_->cloud = cloud;
  impl_->radius = radius;
  if (!cloud->empty()) impl_->grid = tolerance_grid(*cloud, radius);
  if (impl_->grid) {
    impl_->slot.resize(cloud->size());
    for (int s = 0; s < impl_->grid->size(); ++s) impl_->slot[static_cast<std::size_t>(impl_->grid->row(s))] = s;
  } else if (!cloud->empty()) {
    impl_->tree.setInputCloud(cloud);
  }
}

RadiusSearch::~RadiusSearch() = default;

void RadiusSearch::near(int i, std::vector<int>& out) const {
  out.clear();
  const Cloud& cloud = *impl_->cloud;
  const auto& p = cloud[static_cast<std::size_t>(i)];
  if (!impl_->grid) {
    pcl::Indices nn;
    std::vector<float> d2;
    impl_->tree.radiusSearch(p, impl_->radius, nn, d2);
    out.assign(nn.begin(), nn.end());
  } else {
    const UniformGrid& grid = *impl_->grid;
    const float r2 = static_cast<float>(impl_->radius * impl_->radius);  // PCL's kd-tree: float(radius^2), strict <
    const auto [c0, c1] = cells_around(grid, grid.cell(impl_->slot[static_cast<std::size_t>(i)]));
    grid.for_each_in_cells(c0, c1, [&](int s) {
      const auto j = static_cast<int>(grid.row(s));
      if (flann_squared(p, cloud[static_cast<std::size_t>(j)]) < r2) out.push_back(j);
    });
  }
  std::sort(out.begin(), out.end());
}

std::vector<std::vector<int>> euclidean_clusters(const Cloud::ConstPtr& cloud, double tolerance) {
  const auto n = static_cast<Eigen::Index>(cloud->size());
  if (n == 0) return {};
  const std::optional<UniformGrid> found = tolerance_grid(*cloud, tolerance);
  if (!found) return pcl_clusters(cloud, tolerance);
  const UniformGrid& grid = *found;
  const float r2 = static_cast<float>(tolerance * tolerance);  // PCL's kd-tree: float(radius^2), strict <
  std::vector<int> parent(static_cast<std::size_t>(n));
  std::iota(parent.begin(), parent.end(), 0);
  for (int i = 0; i < grid.size(); ++i) {
    const auto& c = grid.cell(i);
    const auto ri = grid.row(i);
    const auto& p = (*cloud)[static_cast<std::size_t>(ri)];
    const auto [c0, c1] = cells_around(grid, c);
    grid.for_each_in_cells(c0, c1, [&](int j) {
      if (j <= i) return;
      const float d2 = flann_squared(p, (*cloud)[static_cast<std::size_t>(grid.row(j))]);
      if (!(d2 < r2)) return;
      const int a = find_root(parent, static_cast<int>(ri)), b = find_root(parent, static_cast<int>(grid.row(j)));
      if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);  // the root: the lowest row
    });
  }
  std::vector<int> slot(static_cast<std::size_t>(n), -1);
  std::vector<std::vector<int>> out;
  for (int i = 0; i < static_cast<int>(n); ++i) {  // roots are their cluster's lowest row: clusters in seed order
    const int r = find_root(parent, i);
    if (slot[static_cast<std::size_t>(r)] < 0) {
      slot[static_cast<std::size_t>(r)] = static_cast<int>(out.size());
      out.emplace_back();
    }
    out[static_cast<std::size_t>(slot[static_cast<std::size_t>(r)])].push_back(i);
  }
  return out;
}

VoxelCells voxel_grid(const Cloud& cloud, float leaf) {
  const float inv = 1.0f / leaf;  // PCL: inverse_leaf_size_ = 1 / leaf_size_ in float
  Eigen::Array3f lo = Eigen::Array3f::Constant(std::numeric_limits<float>::max()), hi = -lo;
  for (const auto& p : cloud) {
    const Eigen::Array3f q(p.x, p.y, p.z);
    lo = lo.min(q);
    hi = hi.max(q);
  }
  std::int64_t span = 1;
  Eigen::Array3i min_b, div_b;
  for (int k = 0; k < 3; ++k) {
    span *= static_cast<std::int64_t>((hi[k] - lo[k]) * inv) + 1;
    min_b[k] = static_cast<int>(std::floor(lo[k] * inv));
    div_b[k] = static_cast<int>(std::floor(hi[k] * inv)) - min_b[k] + 1;
  }
  const std::int64_t n_cells = std::int64_t{div_b[0]} * div_b[1] * div_b[2];
  if (span > std::numeric_limits<std::int32_t>::max() || n_cells > std::numeric_limits<std::int32_t>::max()) {
    throw std::invalid_argument("voxel grid: too many cells for 32-bit indices (crop the cloud or use a larger leaf)");
  }
  const int mul1 = div_b[0], mul2 = div_b[0] * div_b[1];
  const Eigen::Array3f min_f = min_b.cast<float>();
  std::vector<CellRow> cells(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const auto& p = cloud[i];
    const int i0 = static_cast<int>(std::floor(p.x * inv) - min_f[0]);
    const int i1 = static_cast<int>(std::floor(p.y * inv) - min_f[1]);
    const int i2 = static_cast<int>(std::floor(p.z * inv) - min_f[2]);
    cells[i] = {static_cast<unsigned int>(i0 + i1 * mul1 + i2 * mul2), static_cast<unsigned int>(i)};
  }
  boost::sort::spreadsort::integer_sort(cells.begin(), cells.end(),
                                        [](const CellRow& c, unsigned offset) { return c.idx >> offset; });
  VoxelCells out;
  out.centroids.reset(new Cloud);
  out.voxel_of_point.resize(cloud.size());
  for (std::size_t first = 0; first < cells.size();) {
    std::size_t last = first + 1;
    while (last < cells.size() && cells[last].idx == cells[first].idx) ++last;
    Eigen::Vector4f c = Eigen::Vector4f::Zero();  // PCL sums getVector4fMap() in float, in the sorted order
    const auto v = static_cast<int>(out.centroids->size());
    for (std::size_t j = first; j < last; ++j) {
      c += cloud[cells[j].row].getVector4fMap();
      out.voxel_of_point[cells[j].row] = v;
    }
    c /= static_cast<float>(last - first);
    out.centroids->push_back(pcl::PointXYZ(c[0], c[1], c[2]));
    first = last;
  }
  return out;
}

namespace {

/// PCL's console silenced while it lives: RANSAC prints on stderr when a sample is degenerate or no model is found
/// ("Sample points too similar or collinear!", up to one line per iteration), which fit_plane's caller handles
/// itself (a plane refused, or the error naming what the scene lacks). PCL's level is process-wide: concurrent
/// fits may leave it silenced, never louder than it was.
class QuietPcl {
 public:
  QuietPcl() : level_(pcl::console::getVerbosityLevel()) { pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS); }
  ~QuietPcl() { pcl::console::setVerbosityLevel(level_); }
  QuietPcl(const QuietPcl&) = delete;
  QuietPcl& operator=(const QuietPcl&) = delete;

 private:
  pcl::console::VERBOSITY_LEVEL level_;
};

template <typename Model>
bool fit_plane_with(const Cloud::ConstPtr& cloud, double distance, int iterations, std::uint64_t seed,
                    Eigen::VectorXf& coeffs, pcl::Indices& inliers) {
  const QuietPcl quiet;
  typename Model::Ptr model(new Model(cloud, fold_seed(seed)));
  SeededRansac ransac(model, distance, fold_seed(seed) ^ 0x9e3779b9u);
  ransac.setMaxIterations(iterations);
  if (!ransac.computeModel()) return false;
  ransac.getInliers(inliers);
  ransac.getModelCoefficients(coeffs);
  Eigen::VectorXf refined = coeffs;
  model->optimizeModelCoefficients(inliers, coeffs, refined);
  if (refined.allFinite() && refined.head<3>().norm() > 0) coeffs = refined;
  coeffs /= coeffs.head<3>().norm();
  model->selectWithinDistance(coeffs, distance, inliers);
  return true;
}

}  // namespace

bool fit_plane(const Cloud::ConstPtr& cloud, double distance, int iterations, std::uint64_t seed,
               Eigen::VectorXf& coeffs, pcl::Indices& inliers, PlaneTests tests) {
  return tests == PlaneTests::Fast
             ? fit_plane_with<SeededPlaneModel>(cloud, distance, iterations, seed, coeffs, inliers)
             : fit_plane_with<SeededStockPlaneModel>(cloud, distance, iterations, seed, coeffs, inliers);
}

std::size_t count_within_plane(const Cloud::ConstPtr& cloud, const Eigen::VectorXf& coeffs, double threshold) {
  return SeededPlaneModel(cloud, 0).countWithinDistance(coeffs, threshold);
}

pcl::Indices select_within_plane(const Cloud::ConstPtr& cloud, const Eigen::VectorXf& coeffs, double threshold) {
  pcl::Indices inliers;
  SeededPlaneModel(cloud, 0).selectWithinDistance(coeffs, threshold, inliers);
  return inliers;
}

pcl::Indices statistical_inliers(const Cloud::ConstPtr& cloud, int k, double std_ratio) {
  // pcl::StatisticalOutlierRemoval's statistic (knn_distances.hpp: the same numbers, found faster), then its cut in
  // PCL's arithmetic, so the same points are kept.
  const KnnDistances knn = knn_mean_distances(cloud, k);
  const std::vector<float>& distances = knn.mean;
  const int valid = knn.valid;
  const auto n = static_cast<int>(cloud->size());
  double sum = 0, sq_sum = 0;  // in PCL's order and precision: sums in double, each square in float
  for (const float d : distances) {
    sum += d;
    sq_sum += d * d;
  }
  const double mean = sum / static_cast<double>(valid);
  const double variance = (sq_sum - sum * sum / static_cast<double>(valid)) / (static_cast<double>(valid) - 1);
  const double threshold = mean + std_ratio * std::sqrt(variance);
  pcl::Indices kept;
  for (int i = 0; i < n; ++i)
    if (!(distances[static_cast<std::size_t>(i)] > threshold)) kept.push_back(i);
  return kept;
}

}  // namespace graspmix::detail
