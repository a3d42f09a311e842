#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <random>
#include <stdexcept>
#include <vector>

#include <pcl/filters/statistical_outlier_removal.h>
#include <pcl/filters/voxel_grid.h>
#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/sample_consensus/sac_model_plane.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/extract_clusters.h>

#include "graspmix/perception/cleanup.hpp"
#include "perception/cloud_filters.hpp"
#include "perception/knn_distances.hpp"

using namespace graspmix;

namespace {

/// A 60 x 60 cm table at z = 0.7 (1 mm noise), a 6 x 4 x 8 cm box standing on it, a few outliers.
struct Scene {
  Vec3Array points;
  int n_table = 0, n_object = 0, n_outliers = 0;
};

Scene make_scene(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.001);
  std::vector<Eigen::Vector3d> pts;
  Scene s;
  for (int i = 0; i < 40000; ++i) pts.emplace_back(0.3 * u(rng), 0.3 * u(rng), 0.7 + noise(rng)), ++s.n_table;
  const Eigen::Vector3d e(0.03, 0.02, 0.04), c(0.05, -0.02, 0.74);
  for (int i = 0; i < 8000; ++i) {
    Eigen::Vector3d p(u(rng) * e.x(), u(rng) * e.y(), u(rng) * e.z());
    const int axis = static_cast<int>((u(rng) + 1) * 1.5) % 3;
    p[axis] = (u(rng) < 0 ? -1 : 1) * e[axis];
    if (axis == 2 && p.z() < 0) p.z() = e.z();  // the bottom face is hidden by the table
    pts.push_back(c + p);
    ++s.n_object;
  }
  for (int i = 0; i < 30; ++i) pts.emplace_back(0.3 * u(rng), 0.3 * u(rng), 1.0 + 0.2 * u(rng)), ++s.n_outliers;
  s.points.resize(static_cast<Eigen::Index>(pts.size()), 3);
  for (std::size_t i = 0; i < pts.size(); ++i) s.points.row(static_cast<Eigen::Index>(i)) = pts[i].transpose();
  return s;
}

}  // namespace

TEST(Scene, PlaneRemovalKeepsTheObjectAndFindsTheTable) {
  const Scene sc = make_scene(1);
  CleanupSettings st;
  st.voxel_size = 0.0;
  const CleanupResult r = prepare_cloud(sc.points, st);
  ASSERT_TRUE(r.plane_found);
  EXPECT_NEAR(r.plane[2], 1.0, 1e-3) << "normal up, towards the object";
  EXPECT_NEAR(r.plane[3], -0.7, 1e-3);
  int object = 0, table = 0;
  for (Eigen::Index i = 0; i < r.points.rows(); ++i) {
    const int src = r.indices[i];
    if (src >= sc.n_table && src < sc.n_table + sc.n_object) ++object;
    if (src < sc.n_table) ++table;
  }
  EXPECT_GT(object, 0.93 * sc.n_object);  // the bottom 5 mm of the box sides go with the table
  EXPECT_LT(table, 0.001 * sc.n_table);
  EXPECT_EQ(r.n_input, static_cast<std::size_t>(sc.points.rows()));
  EXPECT_LT(r.n_after_outliers, r.n_input);  // the isolated points went
  for (Eigen::Index i = 0; i < r.points.rows(); ++i) EXPECT_GT(r.points(i, 2), 0.7);
}

TEST(Scene, SameSeedSameResultAndStepsSwitchOff) {
  const Scene sc = make_scene(2);
  CleanupSettings st;
  const CleanupResult a = prepare_cloud(sc.points, st), b = prepare_cloud(sc.points, st);
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.plane, b.plane);
  EXPECT_LT(a.n_after_voxel, a.n_after_crop);
  CleanupSettings off;
  off.voxel_size = 0;
  off.remove_outliers = false;
  off.remove_plane = false;
  const CleanupResult c = prepare_cloud(sc.points, off);
  EXPECT_EQ(c.points.rows(), sc.points.rows());
  EXPECT_FALSE(c.plane_found);
  off.crop = true;
  off.crop_min << -1, -1, 0.71;
  off.crop_max << 1, 1, 0.9;
  const CleanupResult d = prepare_cloud(sc.points, off);
  int inside = 0;
  for (Eigen::Index i = 0; i < sc.points.rows(); ++i)
    inside +=
        sc.points(i, 2) >= 0.71 && sc.points(i, 2) <= 0.9 && sc.points.row(i).head<2>().cwiseAbs().maxCoeff() <= 1;
  EXPECT_EQ(d.points.rows(), inside);
  EXPECT_GT(inside, sc.n_object / 2);
}

TEST(Scene, BadInputThrows) {
  const Scene sc = make_scene(3);
  CleanupSettings st;
  st.voxel_size = -1;
  EXPECT_THROW(prepare_cloud(sc.points, st), std::invalid_argument);
  CleanupSettings crop;
  crop.crop = true;
  crop.crop_min << 5, 5, 5;
  crop.crop_max << 6, 6, 6;
  EXPECT_THROW(prepare_cloud(sc.points, crop), std::invalid_argument);
  EXPECT_THROW(prepare_cloud(Vec3Array(0, 3)), std::invalid_argument);
}

namespace {

/// Brute-force voxel grid: the input rows of each voxel (cell floor(x / leaf) per axis, in float as PCL
/// computes it) keyed by cell, in increasing row order.
std::map<std::array<int, 3>, std::vector<int>> cells_of(const Vec3Array& pts, float leaf) {
  const float inv = 1.0f / leaf;
  std::map<std::array<int, 3>, std::vector<int>> cells;
  for (Eigen::Index i = 0; i < pts.rows(); ++i) {
    std::array<int, 3> c{};
    for (int k = 0; k < 3; ++k) c[k] = static_cast<int>(std::floor(static_cast<float>(pts(i, k)) * inv));
    cells[c].push_back(static_cast<int>(i));
  }
  return cells;
}

/// Random clouds: uniform, snapped to a lattice finer than the voxel (many equal distances: the tie
/// rule), and with every point repeated (exact duplicates in one voxel).
Vec3Array random_cloud(int kind, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  const int n = 6000;
  Vec3Array p(kind == 2 ? 2 * n : n, 3);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) p(i, k) = kind == 1 ? std::round(u(rng) / 0.001) * 0.001 : u(rng);
  if (kind == 2) p.bottomRows(n) = p.topRows(n);
  return p;
}

}  // namespace

TEST(Scene, VoxelCentroidsAndSourcesMatchABruteForceGrid) {
  CleanupSettings st;
  st.voxel_size = 0.004;
  st.remove_outliers = false;
  st.remove_plane = false;
  for (int kind = 0; kind < 3; ++kind) {
    for (std::uint64_t seed = 0; seed < 3; ++seed) {
      const Vec3Array pts = random_cloud(kind, seed);
      const CleanupResult r = prepare_cloud(pts, st);
      const auto cells = cells_of(pts, static_cast<float>(st.voxel_size));
      ASSERT_EQ(static_cast<std::size_t>(r.points.rows()), cells.size());
      std::vector<Eigen::RowVector3d> means;  // in double, for the centroids to be matched with
      std::vector<const std::vector<int>*> voxels;
      for (const auto& [cell, rows] : cells) {
        Eigen::RowVector3d mean = Eigen::RowVector3d::Zero();
        for (const int i : rows) mean += pts.row(i);
        means.push_back(mean / static_cast<double>(rows.size()));
        voxels.push_back(&rows);
      }
      std::vector<char> seen(cells.size(), 0);
      for (Eigen::Index j = 0; j < r.points.rows(); ++j) {
        const std::vector<int>* members = nullptr;  // the voxel whose mean this centroid is (to float precision)
        std::size_t which = 0;
        for (std::size_t v = 0; v < means.size(); ++v)
          if ((means[v] - r.points.row(j)).cwiseAbs().maxCoeff() < 1e-6) members = voxels[v], which = v;
        ASSERT_NE(members, nullptr) << "centroid " << j << " is no voxel's mean";
        EXPECT_FALSE(seen[which]) << "two centroids for one voxel";
        seen[which] = 1;
        // its source: the member nearest to it (float squared distance), the lowest row on a tie
        int best = -1;
        float best_d2 = std::numeric_limits<float>::infinity();
        for (const int i : *members) {
          float d2 = 0;
          for (int k = 0; k < 3; ++k) {
            const float d = static_cast<float>(pts(i, k)) - static_cast<float>(r.points(j, k));
            d2 += d * d;
          }
          if (d2 < best_d2) best = i, best_d2 = d2;
        }
        EXPECT_EQ(r.sources[j], best) << "kind " << kind << " seed " << seed << " centroid " << j;
        EXPECT_EQ(r.indices[j], -1);
      }
    }
  }
}

// The one-pass voxel grid against pcl::VoxelGrid on random clouds (clustered, so voxels hold many points
// in an unsorted order): the same centroids bit for bit, in the same order, and every point's voxel is
// the centroid of the cell PCL puts it in (its getCentroidIndex with the leaf layout saved).
TEST(VoxelGrid, MatchesPclVoxelGridExactly) {
  std::mt19937_64 rng(7);
  std::normal_distribution<float> g(0.0f, 1.0f);
  for (const float leaf : {0.003f, 0.01f, 0.05f}) {
    detail::Cloud::Ptr cloud(new detail::Cloud);
    for (int c = 0; c < 20; ++c) {
      const pcl::PointXYZ mid(0.3f * g(rng), 0.3f * g(rng), 0.7f + 0.1f * g(rng));
      for (int i = 0; i < 2000; ++i)
        cloud->push_back(pcl::PointXYZ(mid.x + 0.02f * g(rng), mid.y + 0.02f * g(rng), mid.z + 0.02f * g(rng)));
    }
    pcl::VoxelGrid<pcl::PointXYZ> grid;
    grid.setLeafSize(leaf, leaf, leaf);
    grid.setSaveLeafLayout(true);
    grid.setInputCloud(cloud);
    detail::Cloud pcl_out;
    grid.filter(pcl_out);
    const detail::VoxelCells mine = detail::voxel_grid(*cloud, leaf);
    ASSERT_EQ(mine.centroids->size(), pcl_out.size());
    for (std::size_t k = 0; k < pcl_out.size(); ++k) {
      EXPECT_EQ((*mine.centroids)[k].x, pcl_out[k].x);
      EXPECT_EQ((*mine.centroids)[k].y, pcl_out[k].y);
      EXPECT_EQ((*mine.centroids)[k].z, pcl_out[k].z);
    }
    ASSERT_EQ(mine.voxel_of_point.size(), cloud->size());
    for (std::size_t i = 0; i < cloud->size(); ++i)
      ASSERT_EQ(mine.voxel_of_point[i], grid.getCentroidIndex((*cloud)[i])) << "point " << i << " leaf " << leaf;
  }
}

TEST(VoxelGrid, RefusesAGridPastThirtyTwoBitIndices) {
  detail::Cloud cloud;
  cloud.push_back(pcl::PointXYZ(0, 0, 0));
  cloud.push_back(pcl::PointXYZ(100, 100, 100));  // 1e5 cells per axis at 1 mm
  EXPECT_THROW(detail::voxel_grid(cloud, 0.001f), std::invalid_argument);
}

namespace {

/// Blobs of points (3 mm spacing, Gaussian) with sparse noise around them: clusters that touch, apart, and
/// single points; outliers of every degree.
detail::Cloud::Ptr blobs(std::uint64_t seed, int n_blobs, int per_blob, int n_noise) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<float> g(0.0f, 1.0f);
  std::uniform_real_distribution<float> u(-0.5f, 0.5f);
  detail::Cloud::Ptr cloud(new detail::Cloud);
  for (int c = 0; c < n_blobs; ++c) {
    const pcl::PointXYZ mid(0.2f * g(rng), 0.2f * g(rng), 0.2f * g(rng));
    for (int i = 0; i < per_blob; ++i)
      cloud->push_back(pcl::PointXYZ(mid.x + 0.01f * g(rng), mid.y + 0.01f * g(rng), mid.z + 0.01f * g(rng)));
  }
  for (int i = 0; i < n_noise; ++i) cloud->push_back(pcl::PointXYZ(u(rng), u(rng), u(rng)));
  std::shuffle(cloud->begin(), cloud->end(), rng);
  return cloud;
}

/// Every stride-th point of scene seed's points as a PCL cloud: a table's and a box's surfaces.
detail::Cloud::Ptr surface_cloud(std::uint64_t seed, int stride) {
  const Scene scene = make_scene(seed);
  detail::Cloud::Ptr out(new detail::Cloud);
  for (Eigen::Index r = 0; r < scene.points.rows(); r += stride)
    out->push_back(pcl::PointXYZ(static_cast<float>(scene.points(r, 0)), static_cast<float>(scene.points(r, 1)),
                                 static_cast<float>(scene.points(r, 2))));
  return out;
}

/// Blobs in scattered noise (seed) with 200 of their points repeated.
detail::Cloud::Ptr with_duplicates(std::uint64_t seed) {
  detail::Cloud::Ptr out = blobs(seed, 4, 300, 400);
  for (std::size_t i = 0; i < 200; ++i) out->push_back((*out)[i * 3]);
  return out;
}

}  // namespace

// The grid's Euclidean clusters against pcl::EuclideanClusterExtraction with a kd-tree: the same clusters.
TEST(EuclideanClusters, MatchPclExtraction) {
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    const detail::Cloud::Ptr cloud = blobs(seed, 12, 400, 3000);
    for (const double tol : {0.002, 0.006, 0.02}) {
      pcl::EuclideanClusterExtraction<pcl::PointXYZ> ec;
      ec.setClusterTolerance(tol);
      ec.setMinClusterSize(1);
      ec.setMaxClusterSize(std::numeric_limits<int>::max());
      ec.setSearchMethod(pcl::search::KdTree<pcl::PointXYZ>::Ptr(new pcl::search::KdTree<pcl::PointXYZ>));
      ec.setInputCloud(cloud);
      std::vector<pcl::PointIndices> found;
      ec.extract(found);
      std::vector<std::vector<int>> expected;
      for (const auto& f : found) {
        expected.emplace_back(f.indices.begin(), f.indices.end());
        std::sort(expected.back().begin(), expected.back().end());
      }
      std::sort(expected.begin(), expected.end());
      const std::vector<std::vector<int>> mine = detail::euclidean_clusters(cloud, tol);
      for (std::size_t c = 1; c < mine.size(); ++c) EXPECT_LT(mine[c - 1].front(), mine[c].front());
      EXPECT_GT(mine.size(), 12u);
      EXPECT_EQ(mine, expected) << "seed " << seed << " tolerance " << tol;
    }
  }
}

// A far stray point makes the grid too large: PCL's own extraction answers, the same clusters.
TEST(EuclideanClusters, FarStrayPointFallsBackToPcl) {
  detail::Cloud::Ptr cloud = blobs(4, 3, 200, 0);
  cloud->push_back(pcl::PointXYZ(1e5f, 0.0f, 0.0f));
  const auto mine = detail::euclidean_clusters(cloud, 0.006);
  std::size_t n = 0;
  for (const auto& c : mine) n += c.size();
  EXPECT_EQ(n, cloud->size());
  EXPECT_EQ(mine.back(), std::vector<int>{static_cast<int>(cloud->size()) - 1});
}

// The grid's radius search against pcl::KdTreeFLANN's radiusSearch on the same cloud: the same neighbours of every
// point (as sorted rows), on blobs in scattered noise, with duplicated points, and on a cloud with a far stray point
// (PCL's own tree then).
TEST(RadiusSearch, MatchesPclKdTree) {
  detail::Cloud::Ptr stray = blobs(12, 3, 200, 50);
  stray->push_back(pcl::PointXYZ(1e5f, 0.0f, 0.0f));
  for (const auto& cloud : {blobs(11, 8, 300, 1500), with_duplicates(13), stray}) {
    pcl::KdTreeFLANN<pcl::PointXYZ> tree;
    tree.setInputCloud(cloud);
    for (const double radius : {0.004, 0.008, 0.03}) {
      const detail::RadiusSearch near(cloud, radius);
      std::vector<int> got;
      pcl::Indices nn;
      std::vector<float> d2;
      std::size_t pairs = 0;
      for (std::size_t i = 0; i < cloud->size(); ++i) {
        tree.radiusSearch((*cloud)[i], radius, nn, d2);
        std::vector<int> expected(nn.begin(), nn.end());
        std::sort(expected.begin(), expected.end());
        near.near(static_cast<int>(i), got);
        ASSERT_EQ(got, expected) << cloud->size() << " points, radius " << radius << ", point " << i;
        pairs += expected.size() - 1;
      }
      EXPECT_GT(pairs, cloud->size());  // points have neighbours: the test can tell
    }
  }
}

// The parallel outlier filter against pcl::StatisticalOutlierRemoval itself: the same points kept, on a scene's
// surfaces, on blobs in scattered noise and with duplicated points.
TEST(StatisticalInliers, MatchPclOutlierRemoval) {
  const detail::Cloud::Ptr surfaces = surface_cloud(5, 4);
  for (const auto& cloud : {surfaces, blobs(7, 12, 400, 3000), with_duplicates(6)}) {
    for (const int k : {1, 8, 20}) {
      for (const double ratio : {0.5, 2.0}) {
        pcl::StatisticalOutlierRemoval<pcl::PointXYZ> sor;
        sor.setMeanK(k);
        sor.setStddevMulThresh(ratio);
        sor.setInputCloud(cloud);
        pcl::Indices expected;
        sor.filter(expected);
        ASSERT_LT(expected.size(), cloud->size());  // something is dropped: the test can tell
        EXPECT_EQ(detail::statistical_inliers(cloud, k, ratio), expected)
            << cloud->size() << " points, k " << k << ", ratio " << ratio;
      }
    }
  }
}

// The outlier statistic against brute force in FLANN's and PCL's arithmetic (every float squared distance, the
// k + 1 least in increasing order, the square roots of all but the first summed in double) and against PCL's own
// kd-tree's k + 1 nearest summed the same way: the same number for every point, bit for bit, whether the grid
// vouched for it or the kd-tree searched it (both happen here), on a scene's surfaces, on blobs in scattered noise,
// with duplicated points, on a dense blob beside a sparse sheet (crowded cells go to the tree) and with a far stray
// point (wider cells).
TEST(KnnMeanDistances, MatchBruteForceAndPclBitForBit) {
  std::mt19937_64 rng(14);
  std::uniform_real_distribution<float> u(-0.5f, 0.5f);
  detail::Cloud::Ptr uneven(new detail::Cloud);
  for (int i = 0; i < 1500; ++i) uneven->push_back(pcl::PointXYZ(0.005f * u(rng), 0.005f * u(rng), 0.005f * u(rng)));
  for (int i = 0; i < 1500; ++i) uneven->push_back(pcl::PointXYZ(u(rng), u(rng), 0.1f));
  detail::Cloud::Ptr stray = blobs(15, 4, 300, 300);
  stray->push_back(pcl::PointXYZ(400.0f, 0.0f, 0.0f));
  int from_grid = 0, from_tree = 0;
  for (const auto& cloud : {surface_cloud(8, 8), blobs(10, 8, 300, 1500), with_duplicates(9), uneven, stray}) {
    const std::size_t n = cloud->size();
    pcl::KdTreeFLANN<pcl::PointXYZ> tree;
    tree.setInputCloud(cloud);
    std::vector<float> d2(n);
    for (const int k : {1, 8, 20}) {
      const detail::KnnDistances got = detail::knn_mean_distances(cloud, k);
      ASSERT_EQ(got.mean.size(), n);
      EXPECT_EQ(got.valid, static_cast<int>(n));
      from_grid += static_cast<int>(n) - got.from_tree;
      from_tree += got.from_tree;
      pcl::Indices nn;
      std::vector<float> pcl_d2;
      for (std::size_t i = 0; i < n; ++i) {
        const auto& p = (*cloud)[i];
        for (std::size_t j = 0; j < n; ++j) {
          const auto& q = (*cloud)[j];
          float s = 0, d = 0;
          d = p.x - q.x, s += d * d;
          d = p.y - q.y, s += d * d;
          d = p.z - q.z, s += d * d;
          d2[j] = s;
        }
        std::partial_sort(d2.begin(), d2.begin() + k + 1, d2.end());
        ASSERT_EQ(tree.nearestKSearch(p, k + 1, nn, pcl_d2), k + 1);
        double sum = 0, pcl_sum = 0;
        for (int j = 1; j <= k; ++j) {
          sum += std::sqrt(d2[static_cast<std::size_t>(j)]);
          pcl_sum += std::sqrt(pcl_d2[static_cast<std::size_t>(j)]);
        }
        ASSERT_EQ(got.mean[i], static_cast<float>(sum / k)) << n << " points, k " << k << ", point " << i;
        ASSERT_EQ(got.mean[i], static_cast<float>(pcl_sum / k)) << n << " points, k " << k << ", point " << i;
      }
    }
  }
  EXPECT_GT(from_grid, 0);
  EXPECT_GT(from_tree, 0);
}

// fit_plane's cheaper point test: the same plane and inliers as PCL's own RANSAC and plane model, on a tilted
// noisy plane with clutter and on a cloud with no dominant plane (every iteration runs).
TEST(FitPlane, MatchesPclRansac) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<float> u(-0.5f, 0.5f);
  std::normal_distribution<float> g(0.0f, 0.002f);
  const Eigen::Vector3f n = Eigen::Vector3f(0.1f, -0.2f, 1.0f).normalized();
  const Eigen::Vector3f a = n.unitOrthogonal(), b = n.cross(a);
  for (const int size : {5000, 60000}) {
    for (const bool planar : {true, false}) {
      detail::Cloud::Ptr cloud(new detail::Cloud);
      for (int i = 0; i < size; ++i) {
        const Eigen::Vector3f p = planar && i % 5 != 0 ? Eigen::Vector3f(u(rng) * a + u(rng) * b + g(rng) * n)
                                                       : Eigen::Vector3f(u(rng), u(rng), u(rng));
        cloud->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
      }
      Eigen::VectorXf mine, ref;
      pcl::Indices mine_in, ref_in;
      ASSERT_TRUE(detail::fit_plane(cloud, 0.005, 200, 3, mine, mine_in));
      ASSERT_TRUE(detail::fit_plane(cloud, 0.005, 200, 3, ref, ref_in, detail::PlaneTests::Stock));
      EXPECT_EQ(mine, ref) << size << " points, planar " << planar;
      EXPECT_EQ(mine_in, ref_in) << size << " points, planar " << planar;
      if (planar) {
        EXPECT_GT(std::abs(mine.head<3>().dot(n)), 0.999f);
      }
    }
  }
}

// The point test on its own, against PCL's countWithinDistance, with every point within a few float roundings
// of the threshold (an other order of the dot product's sums passes other points here).
TEST(FitPlane, PointTestPassesThePointsPclPasses) {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<float> u(-0.5f, 0.5f);
  const Eigen::Vector3f n = Eigen::Vector3f(0.3f, -0.2f, 1.0f).normalized(), o(0.7f, 0.2f, -0.3f);
  const double threshold = 0.005;
  detail::Cloud::Ptr cloud(new detail::Cloud);
  for (int i = 0; i < 50000; ++i) {
    Eigen::Vector3f b(u(rng), u(rng), 0.0f);
    b -= n * n.dot(b);
    const float t = static_cast<float>(threshold) * (1.0f + static_cast<float>(i % 41 - 20) * 1.2e-7f);
    const Eigen::Vector3f p = o + b + (i % 2 ? t : -t) * n;
    cloud->push_back(pcl::PointXYZ(p.x(), p.y(), p.z()));
  }
  pcl::SampleConsensusModelPlane<pcl::PointXYZ> pcl_model(cloud);
  for (int h = 0; h < 50; ++h) {
    const Eigen::Vector3f m = (n + 1e-4f * Eigen::Vector3f(u(rng), u(rng), u(rng))).normalized();
    Eigen::VectorXf coeffs(4);
    coeffs << m.x(), m.y(), m.z(), -m.dot(o) + 1e-5f * u(rng);
    pcl::Indices expected;
    pcl_model.selectWithinDistance(coeffs, threshold, expected);
    ASSERT_GT(expected.size(), 1000u);
    ASSERT_LT(expected.size(), cloud->size() - 1000u);
    EXPECT_EQ(detail::count_within_plane(cloud, coeffs, threshold), pcl_model.countWithinDistance(coeffs, threshold));
    EXPECT_EQ(detail::select_within_plane(cloud, coeffs, threshold), expected);
  }
}
