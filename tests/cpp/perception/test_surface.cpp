// compute_surface_features against analytic answers: on a sphere of radius R PCL's k1 ~ k2 ~
// (r / 2R)^2 for search radius r (the per-axis variance of normals tilted by ~d/R over a disc of
// radius r); a cylinder has k1 ~ (r / 2R)^2, k2 ~ 0 with the direction along the circumference; a
// plane has both ~ 0.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <stdexcept>

#include <Eigen/Geometry>

#include "graspmix/perception/surface.hpp"

using namespace graspmix;

namespace {

Vec3Array sphere(double R, int n, std::uint64_t seed, Eigen::Vector3d c = Eigen::Vector3d(0.1, -0.2, 0.3)) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g;
  Vec3Array P(n, 3);
  for (int i = 0; i < n; ++i) {
    Eigen::Vector3d v(g(rng), g(rng), g(rng));
    P.row(i) = (c + R * v.normalized()).transpose();
  }
  return P;
}

/// Side of a cylinder along z (radius R, height h) with both caps, uniform by area.
Vec3Array cylinder(double R, double h, int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double side = 2 * M_PI * R * h, cap = M_PI * R * R;
  Vec3Array P(n, 3);
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * u(rng);
    if (u(rng) * (side + 2 * cap) < side) {
      P.row(i) << R * std::cos(a), R * std::sin(a), h * (u(rng) - 0.5);
    } else {
      const double rr = R * std::sqrt(u(rng));
      P.row(i) << rr * std::cos(a), rr * std::sin(a), (u(rng) < 0.5 ? -0.5 : 0.5) * h;
    }
  }
  return P;
}

/// Surface of an axis-aligned box of half sizes e, uniform by area.
Vec3Array box(const Eigen::Vector3d& e, int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double area[3] = {e.y() * e.z(), e.x() * e.z(), e.x() * e.y()};  // faces normal to x, y, z
  const double total = area[0] + area[1] + area[2];
  Vec3Array P(n, 3);
  for (int i = 0; i < n; ++i) {
    const double pick = (u(rng) + 1) / 2 * total;
    const int axis = pick < area[0] ? 0 : (pick < area[0] + area[1] ? 1 : 2);
    Eigen::Vector3d p(u(rng) * e.x(), u(rng) * e.y(), u(rng) * e.z());
    p[axis] = (u(rng) < 0 ? -1 : 1) * e[axis];
    P.row(i) = p.transpose();
  }
  return P;
}

/// Torus around z with major radius a, tube radius b, uniform by area (rejection on the tube angle).
Vec3Array torus(double a, double b, int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Vec3Array P(n, 3);
  for (int i = 0; i < n;) {
    const double th = 2 * M_PI * u(rng), ph = 2 * M_PI * u(rng);
    if (u(rng) * (a + b) > a + b * std::cos(th)) continue;
    P.row(i++) << (a + b * std::cos(th)) * std::cos(ph), (a + b * std::cos(th)) * std::sin(ph), b * std::sin(th);
  }
  return P;
}

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

Eigen::Matrix3d rotation(const PoseArray& F, Eigen::Index i) {
  return Eigen::Quaterniond(F(i, 6), F(i, 3), F(i, 4), F(i, 5)).toRotationMatrix();
}

void expect_valid_frames(const SurfaceCloud& s) {
  ASSERT_EQ(s.frames.rows(), s.points.rows());
  for (Eigen::Index i = 0; i < s.frames.rows(); ++i) {
    ASSERT_TRUE(s.frames.row(i).allFinite()) << i;
    const Eigen::Vector4d q = s.frames.row(i).tail<4>().transpose();
    EXPECT_NEAR(q.norm(), 1.0, 1e-9);
    EXPECT_GE(q[3], 0.0);
    const Eigen::Matrix3d R = rotation(s.frames, i);
    EXPECT_TRUE((R.transpose() * R).isApprox(Eigen::Matrix3d::Identity(), 1e-9));
    EXPECT_NEAR(R.determinant(), 1.0, 1e-9);
    EXPECT_NEAR(R.col(0).cross(R.col(1)).dot(R.col(2)), 1.0, 1e-9);  // right-handed: x cross y = z
    EXPECT_LT((R.col(2) - s.normals.row(i).transpose()).norm(), 1e-9);
    EXPECT_LT((s.frames.row(i).head<3>() - s.points.row(i)).norm(), 1e-12);
    EXPECT_NEAR(s.normals.row(i).norm(), 1.0, 1e-9);
    EXPECT_GE(s.curvatures(i, 0), s.curvatures(i, 1));
    EXPECT_GE(s.curvatures(i, 1), 0.0);
  }
}

}  // namespace

class SphereRadius : public ::testing::TestWithParam<double> {};

TEST_P(SphereRadius, CurvaturesEqualAndNormalsRadialOutward) {
  const double R = GetParam(), r = 0.01;
  const Eigen::Vector3d c(0.1, -0.2, 0.3);
  const int n = static_cast<int>(4 * M_PI * R * R * 4e5);  // 40 points per cm^2
  const SurfaceCloud s = compute_surface_features(sphere(R, n, 7, c));
  expect_valid_frames(s);
  EXPECT_LE(s.n_dropped, static_cast<std::size_t>(n / 100));
  EXPECT_EQ(s.orientation, "propagate");
  std::vector<double> k1, k2, radial;
  for (Eigen::Index i = 0; i < s.points.rows(); ++i) {
    k1.push_back(s.curvatures(i, 0));
    k2.push_back(s.curvatures(i, 1));
    radial.push_back(s.normals.row(i).dot((s.points.row(i).transpose() - c).normalized()));
  }
  const double expected = std::pow(r / (2 * R), 2);
  EXPECT_NEAR(median(k1), expected, 0.2 * expected) << "R " << R;
  EXPECT_NEAR(median(k2), expected, 0.2 * expected) << "R " << R;
  EXPECT_LT(median(k1) - median(k2), 0.25 * median(k1));
  EXPECT_GT(*std::min_element(radial.begin(), radial.end()), 0.98) << "every normal radial and outward";
  // k1 ~ k2 everywhere: the deterministic frame rule decides x nearly everywhere.
  EXPECT_GT(s.isotropic.cast<double>().mean(), 0.8);
}

INSTANTIATE_TEST_SUITE_P(Radii, SphereRadius, ::testing::Values(0.03, 0.05, 0.08));

TEST(Surface, SphereSearchRadiusScalesCurvatureQuadratically) {
  const double R = 0.05;
  const Vec3Array P = sphere(R, 12566, 3);
  for (double r : {0.008, 0.015}) {
    SurfaceFeatureSettings fs;
    fs.radius = r;
    const SurfaceCloud s = compute_surface_features(P, fs);
    std::vector<double> k1(s.curvatures.col(0).data(), s.curvatures.col(0).data() + s.curvatures.rows());
    const double expected = std::pow(r / (2 * R), 2);
    EXPECT_NEAR(median(k1), expected, 0.2 * expected) << "radius " << r;
  }
}

TEST(Surface, CylinderDirectionAlongCircumference) {
  const double R = 0.03, h = 0.12;
  const SurfaceCloud s = compute_surface_features(cylinder(R, h, 12000, 11));
  expect_valid_frames(s);
  std::vector<double> k1, k2, axial, radial;
  int n_side = 0, anisotropic = 0;
  for (Eigen::Index i = 0; i < s.points.rows(); ++i) {
    const Eigen::Vector3d p = s.points.row(i).transpose();
    const double rho = p.head<2>().norm();
    if (std::abs(rho - R) > 1e-9 || std::abs(p.z()) > h / 2 - 0.015) continue;  // side, away from the rims
    ++n_side;
    k1.push_back(s.curvatures(i, 0));
    k2.push_back(s.curvatures(i, 1));
    const Eigen::Matrix3d F = rotation(s.frames, i);
    axial.push_back(std::abs(F.col(0).z()));
    radial.push_back(F.col(2).dot(Eigen::Vector3d(p.x(), p.y(), 0).normalized()));
    anisotropic += !s.isotropic[i];
  }
  ASSERT_GT(n_side, 5000);
  const double expected = std::pow(0.01 / (2 * R), 2);
  EXPECT_NEAR(median(k1), expected, 0.2 * expected);
  EXPECT_LT(median(k2), 0.1 * median(k1));
  EXPECT_GT(anisotropic, 0.99 * n_side);
  EXPECT_LT(median(axial), 0.05) << "x should run along the circumference, not the axis";
  EXPECT_LT(*std::max_element(axial.begin(), axial.end()), 0.3);
  EXPECT_GT(*std::min_element(radial.begin(), radial.end()), 0.98);
}

TEST(Surface, PlaneIsFlatAndFramesFollowTheRule) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  Vec3Array P(4000, 3);
  for (int i = 0; i < 4000; ++i) P.row(i) << u(rng), u(rng), 0.02;  // a table top, normal +-z
  Vec3Array vp(1, 3);
  vp << 0.0, 0.0, 0.5;
  const SurfaceCloud s = compute_surface_features(P, {}, {}, vp);
  expect_valid_frames(s);
  EXPECT_EQ(s.orientation, "viewpoint");
  EXPECT_LT(s.curvatures.col(0).maxCoeff(), 1e-6);
  for (Eigen::Index i = 0; i < s.points.rows(); ++i) {
    EXPECT_GT(s.normals(i, 2), 0.999);
    ASSERT_TRUE(s.isotropic[i]);
    EXPECT_NEAR(s.frame_ambiguity[i], M_PI, 1e-9);
    // Normal within 26 degrees of z: x is world x projected on the tangent plane.
    EXPECT_GT(rotation(s.frames, i).col(0).x(), 0.999);
  }
}

TEST(Surface, IsotropicFrameOnASphereSideIsProjectedWorldZ) {
  const SurfaceCloud s = compute_surface_features(sphere(0.05, 12566, 9, Eigen::Vector3d::Zero()));
  int checked = 0;
  for (Eigen::Index i = 0; i < s.points.rows(); ++i) {
    const Eigen::Vector3d nrm = s.normals.row(i).transpose();
    if (!s.isotropic[i] || std::abs(nrm.z()) > 0.8) continue;
    const Eigen::Vector3d up = (Eigen::Vector3d::UnitZ() - nrm.z() * nrm).normalized();
    EXPECT_GT(rotation(s.frames, i).col(0).dot(up), 1 - 1e-9);
    ++checked;
  }
  EXPECT_GT(checked, 4000);
}

TEST(Surface, BoxEdgesCurveMoreThanFaces) {
  const Eigen::Vector3d e(0.05, 0.03, 0.02);
  const SurfaceCloud s = compute_surface_features(box(e, 12000, 13));
  expect_valid_frames(s);
  std::vector<double> edge, face;
  int outward = 0, n_face = 0;
  for (Eigen::Index i = 0; i < s.points.rows(); ++i) {
    const Eigen::Vector3d p = s.points.row(i).transpose();
    // Distance to the nearest edge: the second smallest distance to a face plane.
    Eigen::Vector3d gap = (e - p.cwiseAbs());
    std::sort(gap.data(), gap.data() + 3);
    if (gap[1] < 0.002) edge.push_back(s.curvatures(i, 0));
    if (gap[1] > 0.022) {  // beyond the reach of the neighbours' normals (2 radii)
      face.push_back(s.curvatures(i, 0));
      int axis;
      (p.cwiseAbs() - e).maxCoeff(&axis);
      outward += s.normals(i, axis) * (p[axis] > 0 ? 1 : -1) > 0.99;
      ++n_face;
    }
  }
  ASSERT_GT(edge.size(), 200u);
  ASSERT_GT(face.size(), 500u);
  EXPECT_GT(median(edge), 10 * median(face));
  EXPECT_LT(median(face), 1e-4);
  EXPECT_EQ(outward, n_face) << "face normals must point out of the box";
}

TEST(Surface, TorusNormalsOutwardWherePointingAtTheCentroidIsWrong) {
  const double a = 0.05, b = 0.02;
  const Vec3Array P = torus(a, b, 16000, 17);
  auto fraction_outward = [&](const SurfaceCloud& s) {
    int good = 0;
    for (Eigen::Index i = 0; i < s.points.rows(); ++i) {
      const Eigen::Vector3d p = s.points.row(i).transpose();
      const Eigen::Vector3d ring = a * Eigen::Vector3d(p.x(), p.y(), 0).normalized();
      good += s.normals.row(i).dot((p - ring).normalized()) > 0.95;
    }
    return static_cast<double>(good) / static_cast<double>(s.points.rows());
  };
  EXPECT_GT(fraction_outward(compute_surface_features(P)), 0.995);
  SurfaceFeatureSettings centroid;
  centroid.orientation = NormalOrientation::Centroid;
  EXPECT_LT(fraction_outward(compute_surface_features(P, centroid)), 0.9) << "the test must be able to fail";
}

TEST(Surface, ShuffledCloudGivesTheSameFeatures) {
  const Vec3Array P = cylinder(0.03, 0.1, 12000, 19);
  std::vector<int> perm(P.rows());
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), std::mt19937_64(23));
  Vec3Array Q(P.rows(), 3);
  for (Eigen::Index i = 0; i < P.rows(); ++i) Q.row(i) = P.row(perm[static_cast<std::size_t>(i)]);
  const SurfaceCloud a = compute_surface_features(P), b = compute_surface_features(Q);
  ASSERT_EQ(a.points.rows(), b.points.rows());
  std::vector<Eigen::Index> row_of(P.rows(), -1);
  for (Eigen::Index r = 0; r < a.points.rows(); ++r) row_of[static_cast<std::size_t>(a.indices[r])] = r;
  for (Eigen::Index r = 0; r < b.points.rows(); ++r) {
    const Eigen::Index ra = row_of[static_cast<std::size_t>(perm[static_cast<std::size_t>(b.indices[r])])];
    ASSERT_GE(ra, 0);
    // Bit for bit: the computation runs in a canonical order of the points.
    ASSERT_EQ(a.normals.row(ra), b.normals.row(r));
    ASSERT_EQ(a.curvatures.row(ra), b.curvatures.row(r));
    ASSERT_EQ(a.frames.row(ra), b.frames.row(r));
    ASSERT_EQ(a.neighbours[ra], b.neighbours[r]);
  }
}

TEST(Surface, ThreadCountDoesNotChangeResults) {
  const Vec3Array P = box(Eigen::Vector3d(0.04, 0.03, 0.02), 8000, 29);
  SurfaceFeatureSettings one, two;
  one.n_threads = 1;
  two.n_threads = 2;
  const SurfaceCloud a = compute_surface_features(P, one), b = compute_surface_features(P, two);
  EXPECT_EQ(a.indices, b.indices);
  EXPECT_EQ(a.frames, b.frames);
  EXPECT_EQ(a.curvatures, b.curvatures);
}

TEST(Surface, SparsePointsAreDroppedNeverNaN) {
  Vec3Array P = sphere(0.04, 8000, 31);
  Vec3Array Q(P.rows() + 3, 3);
  Q.topRows(P.rows()) = P;
  Q.bottomRows(3) << 1, 1, 1, -1, 0, 0, 0.5, 0.5, 0.5;  // isolated: no neighbour within 1 cm
  const SurfaceCloud s = compute_surface_features(Q);
  EXPECT_GE(s.n_dropped, 3u);
  EXPECT_EQ(s.n_input, static_cast<std::size_t>(Q.rows()));
  EXPECT_TRUE(s.frames.allFinite() && s.curvatures.allFinite() && s.normals.allFinite());
  EXPECT_LT(s.indices.maxCoeff(), P.rows());
  EXPECT_GE(s.neighbours.minCoeff(), 10);
}

TEST(Surface, BadInputThrows) {
  const Vec3Array P = sphere(0.04, 2000, 37);
  SurfaceFeatureSettings tiny;
  tiny.radius = 1e-5;
  try {
    compute_surface_features(P, tiny);
    FAIL() << "expected invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no point has a stable neighbourhood"), std::string::npos) << e.what();
  }
  SurfaceFeatureSettings neg;
  neg.radius = -1;
  EXPECT_THROW(compute_surface_features(P, neg), std::invalid_argument);
  EXPECT_THROW(compute_surface_features(Vec3Array(0, 3)), std::invalid_argument);
  Vec3Array nanp = P;
  nanp(5, 1) = std::nan("");
  EXPECT_THROW(compute_surface_features(nanp), std::invalid_argument);
  EXPECT_THROW(compute_surface_features(P, {}, Vec3Array::Zero(P.rows(), 3)), std::invalid_argument);
  EXPECT_THROW(compute_surface_features(P, {}, {}, Vec3Array::Zero(2, 3)), std::invalid_argument);
}

TEST(Surface, GivenNormalsAreKeptAndViewpointsPerPointOrient) {
  const Eigen::Vector3d c(0, 0, 0);
  const Vec3Array P = sphere(0.05, 12566, 41, c);
  Vec3Array inward = -P.rowwise().normalized();
  const SurfaceCloud kept = compute_surface_features(P, {}, inward);
  EXPECT_EQ(kept.orientation, "given");
  EXPECT_LT(kept.normals.row(0).dot(P.row(kept.indices[0]).normalized()), -0.999);
  // One camera per point, each outside the sphere along the point's direction.
  const Vec3Array cams = 3.0 * P;
  const SurfaceCloud out = compute_surface_features(P, {}, inward, cams);
  EXPECT_EQ(out.orientation, "viewpoint");
  for (Eigen::Index i = 0; i < out.points.rows(); ++i)
    EXPECT_GT(out.normals.row(i).dot(out.points.row(i).normalized()), 0.999);
}

namespace {

std::string error_of(const Vec3Array& P, const SurfaceFeatureSettings& s = {}, const Vec3Array& normals = {}) {
  try {
    compute_surface_features(P, s, normals);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no exception";
}

}  // namespace

TEST(Surface, ThreadCountOutOfRangeIsRefused) {
  const Vec3Array P = sphere(0.04, 2000, 43);
  for (const int n : {5000, kMaxFeatureThreads + 1, -1}) {
    SurfaceFeatureSettings s;
    s.n_threads = n;
    EXPECT_NE(error_of(P, s).find("n_threads"), std::string::npos) << n;
  }
  SurfaceFeatureSettings most;
  most.n_threads = kMaxFeatureThreads;
  EXPECT_NO_THROW(compute_surface_features(P, most));
}

TEST(Surface, DenseCloudIsRefusedAtTheNeighbourCap) {
  // 200k points on a 1 cm sphere: every 1 cm neighbourhood holds tens of thousands of points; without
  // the cap this runs for minutes, with it the first neighbourhood stops it.
  const Vec3Array P = sphere(0.01, 200000, 47);
  const std::string m = error_of(P);
  EXPECT_NE(m.find("max_neighbours"), std::string::npos) << m;
  EXPECT_NE(m.find("voxel-downsample"), std::string::npos) << m;
  EXPECT_NE(error_of(P, {}, P.rowwise().normalized()).find("max_neighbours"), std::string::npos);  // given normals
  SurfaceFeatureSettings bad;
  bad.max_neighbours = 5;  // below min_neighbours
  EXPECT_NE(error_of(P, bad).find("max_neighbours"), std::string::npos);
}

TEST(Surface, OrdinaryCloudsNeverReachTheCap) {
  // The paper's setting (1 cm radius) on a sphere as dense as the demonstration clouds: every
  // neighbourhood is far below the default cap, so the results are those without a cap, bit for bit.
  const Vec3Array P = sphere(0.035, 6000, 53);
  SurfaceFeatureSettings uncapped;
  uncapped.max_neighbours = 0;
  const SurfaceCloud a = compute_surface_features(P), b = compute_surface_features(P, uncapped);
  EXPECT_LT(a.neighbours.maxCoeff(), SurfaceFeatureSettings{}.max_neighbours / 10);
  EXPECT_EQ(a.indices, b.indices);
  EXPECT_EQ(a.frames, b.frames);
  EXPECT_EQ(a.curvatures, b.curvatures);
}

TEST(Surface, DegenerateCloudsAreErrorsNotFeatures) {
  // 2,000 copies of one point: zero extent.
  const Vec3Array same = Vec3Array::Constant(2000, 3, 0.25);
  EXPECT_NE(error_of(same).find("coincide"), std::string::npos) << error_of(same);
  // Points on a line: every neighbourhood is one-dimensional, so no normal is defined.
  Vec3Array line(2000, 3);
  for (int i = 0; i < 2000; ++i) line.row(i) << 1e-5 * i, 0.5, 0.5;
  EXPECT_NE(error_of(line).find("degenerate"), std::string::npos) << error_of(line);
  // Two bunches of duplicates with given normals: neighbourhoods of zero extent.
  Vec3Array twice(2000, 3);
  twice.topRows(1000).setZero();
  twice.bottomRows(1000).setConstant(0.5);
  const Vec3Array up = Vec3Array::Constant(2000, 3, 1.0);
  EXPECT_NE(error_of(twice, {}, up).find("degenerate"), std::string::npos) << error_of(twice, {}, up);
}
