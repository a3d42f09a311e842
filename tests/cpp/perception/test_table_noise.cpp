#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "graspmix/perception/segmentation.hpp"
#include "perception/table_noise.hpp"

using namespace graspmix;
using detail::table_noise;

namespace {

constexpr double kBand = 0.005;  // SegmentationSettings' plane_distance

/// n heights of a table's points: Gaussian about `centre` with spread sigma (m).
std::vector<double> table(int n, double centre, double sigma, std::mt19937_64& rng) {
  std::normal_distribution<double> g(centre, sigma);
  std::vector<double> h(static_cast<std::size_t>(n));
  for (auto& v : h) v = g(rng);
  return h;
}

std::vector<double> uniform(int n, double lo, double hi, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(lo, hi);
  std::vector<double> h(static_cast<std::size_t>(n));
  for (auto& v : h) v = u(rng);
  return h;
}

Eigen::VectorXd join(std::vector<double> a, const std::vector<double>& b = {}) {
  a.insert(a.end(), b.begin(), b.end());
  return Eigen::Map<const Eigen::VectorXd>(a.data(), static_cast<Eigen::Index>(a.size()));
}

/// A 60 x 60 cm table at z = 0 with Gaussian height noise sigma, and optionally a 6 cm cube's top and one side.
Vec3Array scene(double sigma, bool with_box, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::normal_distribution<double> g(0.0, sigma);
  std::vector<Eigen::Vector3d> p;
  for (int i = 0; i < 20000; ++i) p.emplace_back(0.3 * u(rng), 0.3 * u(rng), g(rng));
  for (int i = 0; with_box && i < 3000; ++i) p.emplace_back(0.03 * u(rng), 0.03 * u(rng), 0.06 + g(rng));
  for (int i = 0; with_box && i < 2000; ++i) p.emplace_back(0.03 * u(rng), 0.03, 0.03 + 0.03 * u(rng));
  Vec3Array out(static_cast<Eigen::Index>(p.size()), 3);
  for (std::size_t i = 0; i < p.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = p[i].transpose();
  return out;
}

}  // namespace

TEST(TableNoise, IsTheSpreadOfGaussianNoiseNarrowerOrWiderThanTheBand) {
  std::mt19937_64 rng(1);
  for (const double sigma : {0.001, 0.003, 0.01}) {
    const auto t = table_noise(join(table(20000, 0.001, sigma, rng)), kBand);
    ASSERT_TRUE(t.known) << sigma;
    EXPECT_NEAR(t.spread, sigma, 0.04 * sigma);
    EXPECT_NEAR(t.centre, 0.001, 0.05 * sigma);
    EXPECT_TRUE(t.holds(0.001 + 4.9 * t.spread));
    EXPECT_FALSE(t.holds(0.001 + 5.1 * t.spread));
  }
}

TEST(TableNoise, WhatStandsOnTheTableAddsLittle) {
  std::mt19937_64 rng(2);
  // A fifth of the points on the sides of objects up to 6 cm tall.
  const auto t = table_noise(join(table(16000, 0.0, 0.002, rng), uniform(4000, 0.0, 0.06, rng)), kBand);
  ASSERT_TRUE(t.known);
  EXPECT_NEAR(t.spread, 0.002, 0.2 * 0.002);
}

TEST(TableNoise, IsUnknownWhereNoTableIs) {
  std::mt19937_64 rng(3);
  // An object's points above a plane given with the table cropped away: nothing behind the plane.
  EXPECT_FALSE(table_noise(join(uniform(5000, 0.004, 0.08, rng)), kBand).known);
  // The top face of a flat box (2 cm) seen without a table: the face's noise, and its sides behind it only.
  EXPECT_FALSE(table_noise(join(table(4000, 0.0, 0.001, rng), uniform(6000, -0.02, -0.001, rng)), kBand).known);
  // Fewer than 3 points near the plane.
  EXPECT_FALSE(table_noise(join({0.5, 0.6, -0.002}), kBand).known);
  // Unknown noise still holds the band about the plane.
  const detail::TableNoise none;
  EXPECT_TRUE(none.holds(-0.004, kBand));
  EXPECT_FALSE(none.holds(0.006, kBand));
}

TEST(TableNoise, ANoisyTableAloneHasNoObjectAndAnObjectOnItIsStillFound) {
  const Vec3Array camera = Eigen::RowVector3d(0.0, 0.0, 1.0);
  for (const double sigma : {0.002, 0.004}) {
    for (std::uint64_t seed = 0; seed < 3; ++seed) {
      try {
        const Segmentation s = segment_scene(scene(sigma, false, seed), camera);
        FAIL() << "sigma " << sigma << ", seed " << seed << ": " << s.objects.size() << " objects";
      } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("no object above the support plane"), std::string::npos) << e.what();
      }
      const Segmentation s = segment_scene(scene(sigma, true, seed), camera);
      ASSERT_TRUE(s.plane_found);
      ASSERT_EQ(s.objects.size(), 1u) << "sigma " << sigma << ", seed " << seed;
      EXPECT_LT(s.objects[0].centroid.head<2>().norm(), 0.01);
      EXPECT_GT(s.objects[0].obb_extents.maxCoeff(), 0.05);  // the cube, not a fragment of the table
      EXPECT_LT(s.objects[0].obb_extents.maxCoeff(), 0.1);
    }
  }
}

TEST(TableNoiseMap, FollowsNoiseThatGrowsAcrossTheTable) {
  // A 1 x 1 m table whose height noise grows from 1 mm at y = -0.5 to 4 mm at y = 0.5 (a camera's near table is
  // noisier than its far one), on a plane tilted 10 degrees about x; each place's spread is the local sigma.
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  std::normal_distribution<double> g(0.0, 1.0);
  const double tilt = 10.0 * M_PI / 180.0;
  const Eigen::Vector3d n(0.0, -std::sin(tilt), std::cos(tilt));  // the plane's normal, through the origin
  const Eigen::Vector3d along(0.0, std::cos(tilt), std::sin(tilt));
  const auto sigma_at = [](double y) { return 0.001 + 0.003 * (y + 0.5); };
  Vec3Array P(200000, 3);
  Eigen::VectorXd h(P.rows());
  for (Eigen::Index r = 0; r < P.rows(); ++r) {
    const double x = u(rng), y = u(rng);
    h[r] = sigma_at(y) * g(rng);
    P.row(r) = (Eigen::Vector3d(x, 0, 0) + y * along + h[r] * n).transpose();
  }
  detail::TableNoiseMap map(P, h, Eigen::Vector4d(n.x(), n.y(), n.z(), 0.0), kBand);
  for (const double y : {-0.4, -0.2, 0.0, 0.2, 0.4}) {
    const detail::TableNoise& t = map.at(y * along);
    ASSERT_TRUE(t.known) << y;
    EXPECT_NEAR(t.spread, sigma_at(y), 0.1 * sigma_at(y)) << y;  // the pooled 15 cm span 0.45 mm of sigma
    EXPECT_NEAR(t.centre, 0.0, 0.2 * sigma_at(y)) << y;
  }
  // Outside the table: nothing measured, nothing held but the band; as far as a double goes, the same.
  EXPECT_FALSE(map.at(Eigen::Vector3d(2.0, 0.0, 0.0)).known);
  EXPECT_FALSE(map.at(Eigen::Vector3d(1e300, -1e300, 0.0)).known);
  // The whole table's noise is one figure between the two ends.
  const detail::TableNoise whole = table_noise(h, kBand);
  EXPECT_GT(whole.spread, 1.5 * sigma_at(-0.4));
  EXPECT_LT(whole.spread, 0.8 * sigma_at(0.4));
}
