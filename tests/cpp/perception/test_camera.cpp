// The pinhole camera against exact answers: projection and back-projection invert each other, the pixel a
// point falls in follows the pixel-centre convention, intrinsics fitted to a cloud made from known ones come
// back to 1e-9, and bad input names what was wrong.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

#include "graspmix/perception/camera.hpp"

using namespace graspmix;

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

/// A depth image of w x h with depths in [0.4, 1.2] m and every 7th pixel without a return.
DepthImage random_depth(int h, int w, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> d(0.4, 1.2);
  DepthImage out(h, w);
  for (int v = 0; v < h; ++v)
    for (int u = 0; u < w; ++u) out(v, u) = (v * w + u) % 7 == 3 ? kNaN : d(rng);
  return out;
}

void expect_throw_naming(const std::function<void()>& f, const std::string& needle) {
  try {
    f();
    ADD_FAILURE() << "no exception, expected one naming '" << needle << "'";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(PinholeCamera, ProjectAndBackProjectInvertEachOther) {
  const PinholeCamera cam(525.5, 530.25, 319.3, 241.7, 640, 480);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-100, 700), d(0.1, 5.0);
  for (int i = 0; i < 1000; ++i) {
    const double uu = u(rng), vv = u(rng), z = d(rng);
    const Eigen::Vector3d p = cam.back_project(uu, vv, z);
    EXPECT_DOUBLE_EQ(p.z(), z);
    const Eigen::Vector2d uv = cam.project(p);
    EXPECT_NEAR(uv.x(), uu, 1e-9);
    EXPECT_NEAR(uv.y(), vv, 1e-9);
  }
  EXPECT_TRUE(cam.project(Eigen::Vector3d(0.1, 0.1, 0.0)).hasNaN());   // in the camera's plane
  EXPECT_TRUE(cam.project(Eigen::Vector3d(0.1, 0.1, -1.0)).hasNaN());  // behind it
  const Eigen::Matrix3d K = cam.matrix();
  EXPECT_EQ(K(0, 0), 525.5);
  EXPECT_EQ(K(1, 2), 241.7);
  EXPECT_EQ(K(2, 2), 1.0);
}

TEST(PinholeCamera, PixelCentresAreAtIntegerCoordinates) {
  const PinholeCamera cam(100, 100, 1.5, 1.0, 4, 3);
  int c = -1, r = -1;
  EXPECT_TRUE(cam.pixel({-0.5, -0.5}, c, r));
  EXPECT_EQ(c, 0);
  EXPECT_EQ(r, 0);
  EXPECT_TRUE(cam.pixel({2.49, 1.51}, c, r));
  EXPECT_EQ(c, 2);
  EXPECT_EQ(r, 2);
  EXPECT_FALSE(cam.pixel({3.5, 1.0}, c, r));  // past the last column
  EXPECT_FALSE(cam.pixel({1.0, 2.5}, c, r));  // past the last row
  EXPECT_FALSE(cam.pixel({-0.51, 1.0}, c, r));
  EXPECT_FALSE(cam.pixel({kNaN, 1.0}, c, r));
}

TEST(PinholeCamera, BackProjectsADepthImageRowByRow) {
  const PinholeCamera cam(50, 55, 9.5, 7.25, 20, 15);
  DepthImage depth = random_depth(15, 20, 1);
  depth(0, 1) = 0.0;   // no return, 16-bit convention
  depth(0, 2) = kInf;  // no return, simulated cameras' convention
  const Vec3Array P = cam.back_project(depth);
  ASSERT_EQ(P.rows(), 300);
  for (int v = 0; v < 15; ++v)
    for (int u = 0; u < 20; ++u) {
      const Eigen::Vector3d p = P.row(v * 20 + u).transpose();
      if (!has_return(depth(v, u))) {
        EXPECT_TRUE(p.hasNaN());
        continue;
      }
      EXPECT_DOUBLE_EQ(p.z(), depth(v, u));
      EXPECT_NEAR(p.x(), (u - 9.5) * depth(v, u) / 50, 1e-15);
      EXPECT_NEAR(p.y(), (v - 7.25) * depth(v, u) / 55, 1e-15);
    }
  expect_throw_naming([&] { cam.back_project(DepthImage::Constant(14, 20, 1.0)); }, "15 x 20");
  depth(3, 4) = -0.5;
  expect_throw_naming([&] { cam.back_project(depth); }, "row 3, column 4");
}

TEST(PinholeCamera, FitRecoversKnownIntrinsics) {
  const PinholeCamera truth(612.375, 608.125, 322.6, 236.9, 160, 120);
  const Vec3Array cloud = truth.back_project(random_depth(120, 160, 5));
  const PinholeFit fit = fit_pinhole(cloud, 120, 160);
  EXPECT_NEAR(fit.camera.fx(), truth.fx(), 1e-9);
  EXPECT_NEAR(fit.camera.fy(), truth.fy(), 1e-9);
  EXPECT_NEAR(fit.camera.cx(), truth.cx(), 1e-9);
  EXPECT_NEAR(fit.camera.cy(), truth.cy(), 1e-9);
  EXPECT_EQ(fit.camera.width(), 160);
  EXPECT_EQ(fit.camera.height(), 120);
  EXPECT_LT(fit.rms_px, 1e-9);
  EXPECT_EQ(fit.n_valid, 120 * 160 - (120 * 160 + 3) / 7);  // every 7th pixel from index 3 has no return
}

TEST(PinholeCamera, FitRefusesWhatIsNotAnOrganizedSensorFrameCloud) {
  const PinholeCamera truth(300, 300, 40, 30, 80, 60);
  const Vec3Array cloud = truth.back_project(random_depth(60, 80, 9));
  expect_throw_naming([&] { fit_pinhole(cloud, 60, 81); }, "needs 4860 rows");
  // The same cloud in a world frame: rotated about x by 90 degrees (z up), so some points have z <= 0 ...
  const Eigen::Matrix3d Rx = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  expect_throw_naming([&] { fit_pinhole(Vec3Array(cloud * Rx.transpose()), 60, 80); }, "z forward");
  // ... or moved: every z > 0, but the points no longer lie on their pixels' rays.
  const Vec3Array moved = cloud.rowwise() + Eigen::RowVector3d(0.3, -0.2, 0.5);
  expect_throw_naming([&] { fit_pinhole(moved, 60, 80); }, "RMS reprojection residual");
  // Shuffled rows: not organized.
  Vec3Array shuffled = cloud;
  std::mt19937_64 rng(2);
  for (Eigen::Index i = shuffled.rows() - 1; i > 0; --i)
    shuffled.row(i).swap(shuffled.row(std::uniform_int_distribution<Eigen::Index>(0, i)(rng)));
  EXPECT_THROW(fit_pinhole(shuffled, 60, 80), std::invalid_argument);
  // Mirrored: x left.
  Vec3Array mirrored = cloud;
  mirrored.col(0) *= -1;
  expect_throw_naming([&] { fit_pinhole(mirrored, 60, 80); }, "not positive");
  // Nothing valid, or one column only.
  expect_throw_naming([&] { fit_pinhole(Vec3Array::Constant(4800, 3, kNaN), 60, 80); }, "two columns and two rows");
  Vec3Array one_column = Vec3Array::Constant(4800, 3, kNaN);
  for (int v = 0; v < 60; ++v) one_column.row(v * 80 + 5) = cloud.row(v * 80 + 5);
  expect_throw_naming([&] { fit_pinhole(one_column, 60, 80); }, "1 column(s)");
  expect_throw_naming([&] { fit_pinhole(cloud, 60, 80, 0.0); }, "RMS residual must be");
}

TEST(PinholeCamera, RefusesBadIntrinsics) {
  expect_throw_naming([] { PinholeCamera(0, 500, 320, 240, 640, 480); }, "fx");
  expect_throw_naming([] { PinholeCamera(500, -1, 320, 240, 640, 480); }, "fy");
  expect_throw_naming([] { PinholeCamera(kNaN, 500, 320, 240, 640, 480); }, "fx");
  expect_throw_naming([] { PinholeCamera(500, kInf, 320, 240, 640, 480); }, "fy");
  expect_throw_naming([] { PinholeCamera(500, 500, kNaN, 240, 640, 480); }, "cx");
  expect_throw_naming([] { PinholeCamera(500, 500, 320, kInf, 640, 480); }, "cy");
  expect_throw_naming([] { PinholeCamera(500, 500, 320, 240, 0, 480); }, "width");
  expect_throw_naming([] { PinholeCamera(500, 500, 320, 240, 640, -3); }, "height");
}

TEST(CameraPose, UnitQuaternionsOnly) {
  Eigen::Matrix<double, 7, 1> pose;
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  pose << 0.1, -0.2, 0.3, q.x(), q.y(), q.z(), q.w();
  const Eigen::Isometry3d T = camera_pose(pose);
  EXPECT_TRUE(T.linear().isApprox(q.toRotationMatrix(), 1e-12));
  EXPECT_TRUE(T.translation().isApprox(Eigen::Vector3d(0.1, -0.2, 0.3)));
  check_rigid(T);
  pose.tail<4>() *= 1.0005;  // within the tolerance: normalised
  EXPECT_TRUE(camera_pose(pose).linear().isApprox(q.toRotationMatrix(), 1e-12));
  pose.tail<4>() *= 2.0;
  expect_throw_naming([&] { camera_pose(pose); }, "not a unit quaternion");
  pose.tail<4>() << 0, 0, 0, 0;
  expect_throw_naming([&] { camera_pose(pose, "pose of camera 2"); }, "pose of camera 2");
  pose << kNaN, 0, 0, 0, 0, 0, 1;
  expect_throw_naming([&] { camera_pose(pose); }, "non-finite");
  Eigen::Isometry3d scaled = T;
  scaled.linear() *= 1.01;
  expect_throw_naming([&] { check_rigid(scaled); }, "orthonormal");
  Eigen::Isometry3d mirrored = T;
  mirrored.linear().col(0) *= -1;
  expect_throw_naming([&] { check_rigid(mirrored); }, "determinant");
}
