// The library's private uniform grid against brute force on random points.
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "core/uniform_grid.hpp"

using graspmix::Vec3Array;
using graspmix::detail::UniformGrid;

namespace {

Vec3Array random_points(int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-0.05, 0.1);
  Vec3Array P(n, 3);
  for (int i = 0; i < n; ++i) P.row(i) << u(rng), u(rng), 0.3 * u(rng);
  // Some duplicates, which only the input row orders.
  for (int i = 0; i < n / 10; ++i) P.row(n - 1 - i) = P.row(i);
  return P;
}

UniformGrid::Cell dims_for(const Vec3Array& P, double h) {
  const Eigen::Vector3d ext = P.colwise().maxCoeff() - P.colwise().minCoeff();
  return {static_cast<std::int64_t>(std::floor(ext.x() / h)) + 1,
          static_cast<std::int64_t>(std::floor(ext.y() / h)) + 1,
          static_cast<std::int64_t>(std::floor(ext.z() / h)) + 1};
}

}  // namespace

class UniformGridLayouts : public ::testing::TestWithParam<UniformGrid::Layout> {};

TEST_P(UniformGridLayouts, RadiusNeighboursAreExactlyTheBruteForceOnes) {
  const Vec3Array P = random_points(800, 3);
  const double r = 0.012;
  const Eigen::Vector3d lo = P.colwise().minCoeff().transpose();
  const UniformGrid grid(P, lo, r, dims_for(P, r), GetParam());
  ASSERT_EQ(grid.size(), 800);
  std::vector<int> nn;
  std::vector<double> d2;
  for (int i = 0; i < grid.size(); ++i) {
    grid.neighbours(i, r * r, nn, d2);
    std::set<Eigen::Index> got, want;
    for (std::size_t a = 0; a < nn.size(); ++a) {
      got.insert(grid.row(nn[a]));
      EXPECT_DOUBLE_EQ(d2[a], (P.row(grid.row(nn[a])) - P.row(grid.row(i))).squaredNorm());
    }
    for (Eigen::Index j = 0; j < P.rows(); ++j)
      if ((P.row(j) - P.row(grid.row(i))).squaredNorm() <= r * r) want.insert(j);
    EXPECT_EQ(got, want) << i;
    EXPECT_TRUE(std::is_sorted(nn.begin(), nn.end()));  // canonical order
  }
}

TEST_P(UniformGridLayouts, BoxQueriesVisitExactlyThePointsOfTheCells) {
  const Vec3Array P = random_points(600, 5);
  const double h = 0.01;
  const Eigen::Vector3d lo = P.colwise().minCoeff().transpose();
  const UniformGrid grid(P, lo, h, dims_for(P, h), GetParam());
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-0.08, 0.15);
  for (int trial = 0; trial < 50; ++trial) {
    Eigen::Vector3d a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng));
    const Eigen::Vector3d bl = a.cwiseMin(b), bh = a.cwiseMax(b);
    const UniformGrid::Cell c0 = grid.cell_of(bl), c1 = grid.cell_of(bh);
    std::vector<int> got;
    grid.for_each_in_cells(c0, c1, [&](int i) { got.push_back(i); });
    EXPECT_TRUE(std::is_sorted(got.begin(), got.end()));
    std::vector<int> want;
    for (int i = 0; i < grid.size(); ++i) {
      const UniformGrid::Cell c = grid.cell_of(P.row(grid.row(i)).transpose());
      EXPECT_EQ(c, grid.cell(i));
      bool in = true;
      for (int k = 0; k < 3; ++k) in = in && c[k] >= c0[k] && c[k] <= c1[k];
      if (in) want.push_back(i);
    }
    EXPECT_EQ(got, want) << trial;
    // Every point inside the box is among them.
    for (int i = 0; i < grid.size(); ++i) {
      const Eigen::Vector3d p = grid.point(i);
      if ((p.array() >= bl.array()).all() && (p.array() <= bh.array()).all()) {
        EXPECT_TRUE(std::binary_search(got.begin(), got.end(), i));
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Layouts, UniformGridLayouts,
                         ::testing::Values(UniformGrid::Layout::Dense, UniformGrid::Layout::Sparse));

TEST(UniformGrid, CanonicalOrderDoesNotDependOnTheInputOrder) {
  const Vec3Array P = random_points(300, 11);
  std::vector<Eigen::Index> perm(300);
  for (int i = 0; i < 300; ++i) perm[static_cast<std::size_t>(i)] = i;
  std::shuffle(perm.begin(), perm.end(), std::mt19937_64(2));
  Vec3Array Q(300, 3);
  for (int i = 0; i < 300; ++i) Q.row(i) = P.row(perm[static_cast<std::size_t>(i)]);
  const Eigen::Vector3d lo = P.colwise().minCoeff().transpose();
  const UniformGrid a(P, lo, 0.01, dims_for(P, 0.01), UniformGrid::Layout::Sparse);
  const UniformGrid b(Q, lo, 0.01, dims_for(P, 0.01), UniformGrid::Layout::Dense);
  for (int i = 0; i < 300; ++i) EXPECT_EQ(a.point(i), b.point(i)) << i;
}

TEST(UniformGrid, ClampsPointsOutsideTheGridIntoTheBorderCells) {
  Vec3Array P(2, 3);
  P << -1, 0.5, 0.5, 5, 0.5, 0.5;
  const UniformGrid grid(P, Eigen::Vector3d::Zero(), 1.0, {2, 2, 2}, UniformGrid::Layout::Dense);
  EXPECT_EQ(grid.cell(0), (UniformGrid::Cell{0, 0, 0}));
  EXPECT_EQ(grid.cell(1), (UniformGrid::Cell{1, 0, 0}));
}

TEST(UniformGrid, EmptyCloud) {
  const UniformGrid grid(Vec3Array(0, 3), Eigen::Vector3d::Zero(), 1.0, {1, 1, 1}, UniformGrid::Layout::Dense);
  EXPECT_EQ(grid.size(), 0);
  int visits = 0;
  grid.for_each_in_cells({0, 0, 0}, {0, 0, 0}, [&](int) { ++visits; });
  EXPECT_EQ(visits, 0);
}

TEST(UniformGrid, CoveringSpansTheBoundsWidenedByThePad) {
  const Vec3Array P = random_points(300, 5);
  const double h = 0.01, pad = 0.01;
  // Unpadded: the cell counts of the points' own extent (dims_for), every point in a cell of its own floor.
  const UniformGrid bare = UniformGrid::covering(P, h);
  EXPECT_EQ(bare.dims(), dims_for(P, h));
  // Padded: a pad's worth of cells more on each side, and no point in a border cell (none is clamped there).
  const UniformGrid padded = UniformGrid::covering(P, h, pad);
  const Eigen::Vector3d ext = P.colwise().maxCoeff() - P.colwise().minCoeff();
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(padded.dims()[k], static_cast<std::int64_t>(std::floor((ext[k] + 2 * pad) / h)) + 1) << k;
    for (int i = 0; i < padded.size(); ++i) {
      EXPECT_GT(padded.cell(i)[k], 0) << k;
      EXPECT_LT(padded.cell(i)[k], padded.dims()[k] - 1) << k;
    }
  }
  // A span of 1e9 cells on one axis is clamped to kMaxCells (sparse), not cast past an integer's range.
  Vec3Array far(2, 3);
  far << 0, 0, 0, 1e9 * h, 0, 0;
  EXPECT_EQ(UniformGrid::covering(far, h).dims()[0], UniformGrid::kMaxCells);
  EXPECT_THROW(UniformGrid::covering(Vec3Array(0, 3), h), std::invalid_argument);
  Vec3Array nan = P;
  nan(4, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(UniformGrid::covering(nan, h), std::invalid_argument);
}
