// The visibility model against exact geometry: depth images ray-cast from planes and a box with known
// intrinsics, so the surface along every pixel's ray is known in closed form; the spherical image of a sampled
// sphere against the sphere's ray intersection; the rule that combines views; bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

#include "graspmix/perception/visibility.hpp"
#include "raycast.hpp"

using namespace graspmix;
using namespace graspmix::test;

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();
const PinholeCamera kCam(60.0, 62.0, 31.7, 24.2, 64, 48);
constexpr double kTol = VisibilitySettings{}.surface_tolerance;

const Eigen::Isometry3d kPose = looking_at({0.15, -0.35, 0.45}, {0.0, 0.02, 0.05});
const Eigen::Vector3d kBoxLo(-0.05, -0.04, 0.0), kBoxHi(0.05, 0.04, 0.12);

/// A box on a table (z = 0) seen by kPose.
double box_on_table(const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  return std::min(hit_box(o, d, kBoxLo, kBoxHi), hit_plane(o, d, Eigen::Vector3d::UnitZ(), 0.0));
}

}  // namespace

TEST(Visibility, FrontoParallelPlaneExactlyAtEveryOffset) {
  // A plane at depth 0.8 m facing the camera: along any ray the surface lies at range |q| 0.8 / z.
  const double depth = 0.8;
  const Eigen::Vector3d n = kPose.linear().col(2);
  const DepthImage image = render(kCam, kPose, [&](const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
    return hit_plane(o, d, n, n.dot(kPose.translation()) + depth);
  });
  const VisibilityModel model = VisibilityModel::from_depth(image, kCam, kPose);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-0.49, 63.49), v(-0.49, 47.49);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d dir = ray(kCam, kPose, u(rng), v(rng));
    for (const double delta :
         {0.2, kTol * (1 + 1e-6), kTol * (1 - 1e-6), 0.0, -kTol * (1 - 1e-6), -kTol * (1 + 1e-6), -0.3}) {
      const Eigen::Vector3d p = kPose.translation() + (depth - delta / dir.norm()) * dir;
      EXPECT_NEAR(model.signed_distance(p), delta, 1e-12);
      const SpaceState want = delta > kTol    ? SpaceState::SeenFree
                              : delta < -kTol ? SpaceState::Unseen
                                              : SpaceState::Surface;
      EXPECT_EQ(model.state(p), want) << "delta " << delta;
    }
  }
  // Outside the image (a ray past its first column or last row) and behind the camera: unseen.
  for (const Eigen::Vector3d& dir : {ray(kCam, kPose, -0.51, 10), ray(kCam, kPose, 20, 47.51)}) {
    const Eigen::Vector3d p = kPose.translation() + 0.4 * dir;
    EXPECT_EQ(model.state(p), SpaceState::Unseen);
    EXPECT_TRUE(std::isnan(model.signed_distance(p)));
  }
  EXPECT_EQ(model.state(kPose.translation() - 0.3 * n), SpaceState::Unseen);
  EXPECT_EQ(model.state(kPose.translation()), SpaceState::Unseen);
}

TEST(Visibility, BoxOnATableAlongEveryPixelsRay) {
  const DepthImage image = render(kCam, kPose, box_on_table);
  const VisibilityModel model = VisibilityModel::from_depth(image, kCam, kPose);
  const ViewInfo& info = model.view(0);
  EXPECT_EQ(info.kind, ViewKind::Pinhole);
  EXPECT_EQ(info.n_returns, 64 * 48);
  EXPECT_TRUE(info.camera && *info.camera == kCam);
  int n_box = 0;
  for (int v = 0; v < kCam.height(); ++v)
    for (int u = 0; u < kCam.width(); ++u) {
      const Eigen::Vector3d dir = ray(kCam, kPose, u, v);
      const double t = image(v, u);
      n_box += hit_box(kPose.translation(), dir, kBoxLo, kBoxHi) < kInf;
      for (const double delta : {0.05, 0.004, -0.004, -0.05}) {
        const Eigen::Vector3d p = kPose.translation() + (t - delta / dir.norm()) * dir;
        EXPECT_NEAR(model.signed_distance(p), delta, 1e-12);
      }
    }
  EXPECT_GT(n_box, 100);  // the box fills a good part of the image
  const Eigen::Vector3d centre = (kBoxLo + kBoxHi) / 2;
  EXPECT_EQ(model.state(centre), SpaceState::Unseen);  // inside the box
  // Above the box's top face, towards the camera: free; behind the box on the table's side: its shadow.
  EXPECT_EQ(model.state(centre + Eigen::Vector3d(0, 0, 0.10)), SpaceState::SeenFree);
  EXPECT_EQ(model.state(Eigen::Vector3d(centre.x(), kBoxHi.y() + 0.005, 0.01)), SpaceState::Unseen);
  EXPECT_EQ(model.state(Eigen::Vector3d(centre.x(), kBoxLo.y() - 0.02, 0.05)), SpaceState::SeenFree);
  EXPECT_EQ(model.state(Eigen::Vector3d(0.1, 0.0, 0.0)), SpaceState::Surface);   // the table, seen
  EXPECT_EQ(model.state(Eigen::Vector3d(0.1, 0.0, -0.02)), SpaceState::Unseen);  // under it
}

TEST(Visibility, APixelWithNoReturnSaysNothingUnlessNoReturnIsFree) {
  DepthImage image = render(kCam, kPose, box_on_table);
  image(20, 30) = kNaN;
  image(21, 30) = 0.0;
  image(22, 30) = kInf;
  VisibilitySettings free;
  free.no_return_is_free = true;
  const VisibilityModel model = VisibilityModel::from_depth(image, kCam, kPose);
  const VisibilityModel optimist = VisibilityModel::from_depth(image, kCam, kPose, free);
  EXPECT_EQ(model.view(0).n_returns, 64 * 48 - 3);
  for (int v = 20; v <= 22; ++v) {
    const Eigen::Vector3d p = kPose.translation() + 0.3 * ray(kCam, kPose, 30.2, v - 0.3);
    EXPECT_EQ(model.state(p), SpaceState::Unseen);
    EXPECT_TRUE(std::isnan(model.signed_distance(p)));
    EXPECT_EQ(optimist.state(p), SpaceState::SeenFree);
    EXPECT_EQ(optimist.signed_distance(p), kInf);
  }
  // The neighbouring pixel is unaffected.
  const Eigen::Vector3d q = kPose.translation() + 0.3 * ray(kCam, kPose, 31, 20);
  EXPECT_EQ(model.state(q), SpaceState::SeenFree);
}

TEST(Visibility, OrganizedCloudFitsItsCameraAndAgreesWithTheDepthImage) {
  DepthImage image = render(kCam, kPose, box_on_table);
  image.block(0, 0, 3, 64).setConstant(kNaN);  // holes
  const Vec3Array cloud = kCam.back_project(image);
  const VisibilityModel organized = VisibilityModel::from_organized(cloud, 48, 64, kPose);
  const VisibilityModel depth = VisibilityModel::from_depth(image, kCam, kPose);
  const PinholeCamera& fitted = *organized.view(0).camera;
  EXPECT_NEAR(fitted.fx(), kCam.fx(), 1e-9);
  EXPECT_NEAR(fitted.fy(), kCam.fy(), 1e-9);
  EXPECT_NEAR(fitted.cx(), kCam.cx(), 1e-9);
  EXPECT_NEAR(fitted.cy(), kCam.cy(), 1e-9);
  EXPECT_LT(organized.view(0).fit_rms_px, 1e-9);
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> x(-0.3, 0.3), z(-0.05, 0.3);
  Vec3Array P(5000, 3);
  for (Eigen::Index i = 0; i < P.rows(); ++i) P.row(i) << x(rng), x(rng), z(rng);
  EXPECT_EQ(organized.classify(P), depth.classify(P));
  const Eigen::VectorXd a = organized.signed_distances(P), b = depth.signed_distances(P);
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    if (std::isnan(b[i])) {
      EXPECT_TRUE(std::isnan(a[i]));
    } else {
      EXPECT_NEAR(a[i], b[i], 1e-9);
    }
  }
}

TEST(Visibility, SphericalImageOfASampledSphere) {
  // A sphere of radius 0.1 m sampled uniformly (200k points) seen from 0.6 m, far from the world's origin.
  const Eigen::Vector3d C(10.0, -20.0, 1.5), V = C + Eigen::Vector3d(0.3, -0.5, 0.1).normalized() * 0.6;
  const double R = 0.1, D = (C - V).norm();
  std::mt19937_64 rng(21);
  std::normal_distribution<double> g;
  Vec3Array points(200000, 3);
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    points.row(i) = (C + R * Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized()).transpose();
  const VisibilityModel model = VisibilityModel::from_points(points, V);
  EXPECT_EQ(model.view(0).kind, ViewKind::Spherical);
  EXPECT_TRUE(model.view(0).T_world_sensor.translation().isApprox(V));
  const double silhouette = std::asin(R / D);
  const Eigen::Vector3d axis = (C - V) / D;
  int n = 0;
  for (int i = 0; i < 2000; ++i) {
    // A direction at angle theta from the centre's: inside half the silhouette's angle, or outside it by 5 bins.
    const double theta = i % 2 ? 0.5 * silhouette * std::sqrt((i % 97) / 97.0) : silhouette + 0.025 + 0.001 * (i % 50);
    const Eigen::Vector3d side = axis.cross(Eigen::Vector3d(g(rng), g(rng), g(rng))).normalized();
    const Eigen::Vector3d dir = Eigen::AngleAxisd(theta, side) * axis;
    if (theta > silhouette) {
      EXPECT_EQ(model.state(V + 0.5 * dir), SpaceState::Unseen) << theta;
      continue;
    }
    ++n;
    const double b = D * std::cos(theta), h = std::sqrt(R * R - D * D * std::sin(theta) * std::sin(theta));
    const double near = b - h, far = b + h;  // where the ray enters and leaves the sphere
    // A bin holds its nearest point: within half the silhouette the range varies by < 2.5 mm across a bin.
    EXPECT_NEAR(model.signed_distance(V + (near - 0.02) * dir), 0.02, 0.003);
    EXPECT_EQ(model.state(V + (near - 0.02) * dir), SpaceState::SeenFree);
    EXPECT_EQ(model.state(V + (near + 0.001) * dir), SpaceState::Surface);
    EXPECT_EQ(model.state(V + (near + 0.03) * dir), SpaceState::Unseen);
    EXPECT_EQ(model.state(V + (far + 0.05) * dir), SpaceState::Unseen);
  }
  EXPECT_GT(n, 900);
  EXPECT_EQ(model.state(V), SpaceState::Unseen);
}

TEST(Visibility, ViewsCombineSurfaceFirstThenFreeThenUnseen) {
  // Two views from one camera of two planes facing it, at depths 1.0 (a) and 1.5 (b).
  const Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  const VisibilityModel a = VisibilityModel::from_depth(DepthImage::Constant(48, 64, 1.0), kCam, T);
  VisibilityModel both = VisibilityModel::from_depth(DepthImage::Constant(48, 64, 1.5), kCam, T);
  both.add_view(a);
  ASSERT_EQ(both.n_views(), 2);
  const auto at = [](double z) { return Eigen::Vector3d(0.0, 0.0, z); };  // on the optical axis: range = depth
  EXPECT_EQ(both.state(at(1.0)), SpaceState::Surface);                    // a: surface, b: free
  EXPECT_NEAR(both.signed_distance(at(1.0)), 0.0, 1e-12);
  EXPECT_EQ(both.state(at(0.5)), SpaceState::SeenFree);  // both free: the larger distance
  EXPECT_NEAR(both.signed_distance(at(0.5)), 1.0, 1e-12);
  EXPECT_EQ(both.state(at(1.2)), SpaceState::SeenFree);  // a: behind, b: free
  EXPECT_NEAR(both.signed_distance(at(1.2)), 0.3, 1e-12);
  EXPECT_EQ(both.state(at(2.0)), SpaceState::Unseen);  // both behind: the lesser depth behind
  EXPECT_NEAR(both.signed_distance(at(2.0)), -0.5, 1e-12);
  EXPECT_EQ(both.state(at(1.5 + kTol / 2)), SpaceState::Surface);
  EXPECT_EQ(both.state(Eigen::Vector3d(5.0, 0.0, 1.0)), SpaceState::Unseen);  // outside both images
  VisibilityModel none;                                                       // no view: nothing seen
  EXPECT_EQ(none.n_views(), 0);
  EXPECT_EQ(none.state(at(1.0)), SpaceState::Unseen);
  EXPECT_TRUE(std::isnan(none.signed_distance(at(1.0))));
  none.add_view(a);
  EXPECT_EQ(none.state(at(0.5)), SpaceState::SeenFree);
  both.add_view(both);  // itself: every view twice, the same answers
  EXPECT_EQ(both.n_views(), 4);
  EXPECT_NEAR(both.signed_distance(at(1.2)), 0.3, 1e-12);
  VisibilitySettings other;
  other.surface_tolerance = 0.01;
  EXPECT_THROW(both.add_view(VisibilityModel::from_depth(DepthImage::Constant(48, 64, 1.0), kCam, T, other)),
               std::invalid_argument);
  EXPECT_THROW(both.view(4), std::out_of_range);
  EXPECT_THROW(both.view(-1), std::out_of_range);
}

TEST(Visibility, TwoCamerasAroundABoxSeeBothSides) {
  const Eigen::Vector3d lo(-0.05, -0.05, -0.05), hi(0.05, 0.05, 0.05);
  const auto box = [&](const Eigen::Vector3d& o, const Eigen::Vector3d& d) { return hit_box(o, d, lo, hi); };
  const Eigen::Isometry3d left = looking_at({-1, 0, 0}, {0, 0, 0}), right = looking_at({1, 0, 0}, {0, 0, 0});
  VisibilityModel model = VisibilityModel::from_depth(render(kCam, left, box), kCam, left);
  const Eigen::Vector3d beyond_right(0.3, 0.0, 0.0), beyond_left(-0.3, 0.0, 0.0);
  EXPECT_EQ(model.state(beyond_right), SpaceState::Unseen);  // the left camera's shadow of the box
  model.add_view(VisibilityModel::from_depth(render(kCam, right, box), kCam, right));
  EXPECT_EQ(model.state(beyond_right), SpaceState::SeenFree);
  EXPECT_EQ(model.state(beyond_left), SpaceState::SeenFree);
  EXPECT_EQ(model.state(Eigen::Vector3d(0, 0, 0)), SpaceState::Unseen);  // inside: neither camera sees it
  EXPECT_EQ(model.state(Eigen::Vector3d(-0.05, 0.01, 0.02)), SpaceState::Surface);
  EXPECT_EQ(model.state(Eigen::Vector3d(0.05, -0.02, 0.0)), SpaceState::Surface);
  // Beside the box both rays return nothing: unseen, unless no return means free.
  EXPECT_EQ(model.state(Eigen::Vector3d(0.0, 0.2, 0.0)), SpaceState::Unseen);
}

TEST(Visibility, FromViewsMakesOneViewPerCamera) {
  // Two spheres' halves, each seen from its own side: per-point viewpoints give two views, each the one
  // from_points makes of that camera's rows, so the answers equal the views added one by one.
  std::mt19937_64 rng(4);
  std::normal_distribution<double> g;
  const Eigen::Vector3d A(-0.6, 0.0, 0.0), B(0.6, 0.0, 0.0);
  // 40k points: 1.8 mm apart on the 10 cm sphere, finer than the 2.5 mm bins at 0.5 m (no empty bin inside).
  Vec3Array points(40000, 3), cams(40000, 3), seen_a(20000, 3), seen_b(20000, 3);
  for (Eigen::Index i = 0; i < 40000; ++i) {
    Eigen::Vector3d d = Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
    const bool from_a = i % 2 == 0;
    if ((d.x() < 0) != from_a) d.x() = -d.x();  // the half facing its camera
    points.row(i) = 0.1 * d.transpose();
    cams.row(i) = (from_a ? A : B).transpose();
    (from_a ? seen_a : seen_b).row(i / 2) = points.row(i);
  }
  const VisibilityModel both = VisibilityModel::from_views(points, cams);
  ASSERT_EQ(both.n_views(), 2);
  EXPECT_TRUE(both.view(0).T_world_sensor.translation().isApprox(A));
  VisibilityModel one_by_one = VisibilityModel::from_points(seen_a, A);
  one_by_one.add_view(VisibilityModel::from_points(seen_b, B));
  std::uniform_real_distribution<double> x(-0.3, 0.3);
  for (int i = 0; i < 2000; ++i) {
    const Eigen::Vector3d p(x(rng), x(rng), x(rng));
    const double d1 = both.signed_distance(p), d2 = one_by_one.signed_distance(p);
    ASSERT_TRUE(d1 == d2 || (std::isnan(d1) && std::isnan(d2))) << p.transpose();
  }
  EXPECT_EQ(both.state(Eigen::Vector3d(0.2, 0, 0)), SpaceState::SeenFree);   // B's side, seen by B
  EXPECT_EQ(both.state(Eigen::Vector3d(-0.2, 0, 0)), SpaceState::SeenFree);  // A's side
  EXPECT_EQ(both.state(Eigen::Vector3d(0, 0, 0)), SpaceState::Unseen);       // inside
  // One row: every point from that camera.
  EXPECT_EQ(VisibilityModel::from_views(points, Vec3Array(A.transpose())).n_views(), 1);
  EXPECT_THROW(VisibilityModel::from_views(points, Vec3Array(3, 3)), std::invalid_argument);
  EXPECT_THROW(VisibilityModel::from_views(points, Vec3Array(0, 3)), std::invalid_argument);
  Vec3Array bad = cams;
  bad(7, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(VisibilityModel::from_views(points, bad), std::invalid_argument);
}

TEST(Visibility, BatchAnswersEqualSinglePointAnswers) {
  const VisibilityModel model = VisibilityModel::from_depth(render(kCam, kPose, box_on_table), kCam, kPose);
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> x(-0.4, 0.4), z(-0.1, 0.5);
  Vec3Array P(20000, 3);  // enough for the parallel loop
  for (Eigen::Index i = 0; i < P.rows(); ++i) P.row(i) << x(rng), x(rng), z(rng);
  const std::vector<SpaceState> states = model.classify(P);
  const Eigen::VectorXd d = model.signed_distances(P);
  int counts[3] = {0, 0, 0};
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    const Eigen::Vector3d p = P.row(i).transpose();
    ASSERT_EQ(states[static_cast<std::size_t>(i)], model.state(p));
    const double di = model.signed_distance(p);
    ASSERT_TRUE(di == d[i] || (std::isnan(di) && std::isnan(d[i])));
    ASSERT_EQ(states[static_cast<std::size_t>(i)], state_of_distance(d[i], kTol));
    ++counts[static_cast<int>(states[static_cast<std::size_t>(i)])];
  }
  EXPECT_GT(counts[0], 1000);
  EXPECT_GT(counts[1], 10);
  EXPECT_GT(counts[2], 1000);
  // The calling thread's batch, on rows that are not a chunk's, and a model of two views (combined point by point).
  std::vector<double> part(3001);
  model.signed_distances_into(P.middleRows(5, 3001), part.data());
  for (Eigen::Index i = 0; i < 3001; ++i)
    ASSERT_TRUE(part[static_cast<std::size_t>(i)] == d[i + 5] || (std::isnan(d[i + 5]) && std::isnan(part[i])));
  VisibilityModel two = model;
  two.add_view(VisibilityModel::from_points(P.topRows(2000), Eigen::Vector3d(0.0, 0.0, 1.0)));
  const Eigen::VectorXd d2 = two.signed_distances(P);
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    const double di = two.signed_distance(P.row(i).transpose());
    ASSERT_TRUE(di == d2[i] || (std::isnan(di) && std::isnan(d2[i])));
  }
}

TEST(Visibility, BadInputNamesWhatWasWrong) {
  const DepthImage good = render(kCam, kPose, box_on_table);
  const auto throws_naming = [](const std::function<void()>& f, const std::string& needle) {
    try {
      f();
      ADD_FAILURE() << "no exception, expected one naming '" << needle << "'";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  throws_naming([&] { VisibilityModel::from_depth(good.topRows(47), kCam, kPose); }, "48 x 64");
  DepthImage negative = good;
  negative(5, 6) = -1.0;
  throws_naming([&] { VisibilityModel::from_depth(negative, kCam, kPose); }, "row 5, column 6");
  throws_naming([&] { VisibilityModel::from_depth(DepthImage::Constant(48, 64, kNaN), kCam, kPose); }, "no pixel");
  throws_naming([&] { VisibilityModel::from_depth(DepthImage::Zero(48, 64), kCam, kPose); }, "no pixel");
  Eigen::Isometry3d scaled = kPose;
  scaled.linear() *= 2.0;
  throws_naming([&] { VisibilityModel::from_depth(good, kCam, scaled); }, "T_world_camera");
  VisibilitySettings s;
  s.surface_tolerance = -0.001;
  throws_naming([&] { VisibilityModel::from_depth(good, kCam, kPose, s); }, "surface_tolerance");
  s = {};
  s.angular_resolution = 0.0;
  throws_naming([&] { VisibilityModel::from_depth(good, kCam, kPose, s); }, "angular_resolution");
  s.angular_resolution = kNaN;
  throws_naming([&] { VisibilityModel::from_depth(good, kCam, kPose, s); }, "angular_resolution");
  s = {};
  s.max_fit_rms = 0.0;
  throws_naming([&] { VisibilityModel::from_depth(good, kCam, kPose, s); }, "max_fit_rms");
  s = {};
  s.max_pixels = 1000;
  throws_naming([&] { VisibilityModel::from_depth(good, kCam, kPose, s); }, "max_pixels");
  // from_points: nothing usable, a bad viewpoint, an image too large.
  const Eigen::Vector3d V(0, 0, 1);
  throws_naming([&] { VisibilityModel::from_points(Vec3Array(0, 3), V); }, "no finite point");
  throws_naming([&] { VisibilityModel::from_points(Vec3Array::Constant(5, 3, kNaN), V); }, "no finite point");
  throws_naming([&] { VisibilityModel::from_points(V.transpose().replicate(4, 1), V); }, "no finite point");
  throws_naming([&] { VisibilityModel::from_points(Vec3Array::Random(50, 3), Eigen::Vector3d(kNaN, 0, 0)); },
                "viewpoint");
  s = {};
  s.angular_resolution = 1e-4;
  s.max_pixels = 1'000'000;
  throws_naming([&] { VisibilityModel::from_points(Vec3Array::Random(50, 3), Eigen::Vector3d(0, 0, 0), s); },
                "max_pixels");
  // from_organized: the fit's errors.
  throws_naming([&] { VisibilityModel::from_organized(kCam.back_project(good), 48, 63, kPose); }, "rows");
}
