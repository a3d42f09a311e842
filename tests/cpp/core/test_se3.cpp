// SE(3) maps against rotation-matrix algebra and known values.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "graspmix/core/se3.hpp"

using namespace graspmix;

namespace {

Eigen::Quaterniond random_quaternion(std::mt19937_64& rng) {
  std::normal_distribution<double> n;
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
}

}  // namespace

TEST(Se3, LogOfAxisAngleIsHalfAngleTimesAxis) {
  const Eigen::Vector3d axis = Eigen::Vector3d(1, 2, -0.5).normalized();
  for (double angle : {0.1, 1.0, 2.5, 3.0}) {
    const Eigen::Quaterniond q(Eigen::AngleAxisd(angle, axis));
    EXPECT_TRUE(quat_log(q).isApprox(0.5 * angle * axis, 1e-12)) << angle;
  }
  EXPECT_TRUE(quat_log(Eigen::Quaterniond::Identity()).isZero(0.0));
}

TEST(Se3, LogTreatsQAndMinusQAlike) {
  std::mt19937_64 rng(1);
  for (int i = 0; i < 100; ++i) {
    const Eigen::Quaterniond q = random_quaternion(rng);
    const Eigen::Quaterniond mq(-q.coeffs());
    EXPECT_TRUE(quat_log(q).isApprox(quat_log(mq), 1e-12));
    EXPECT_LE(quat_log(q).norm(), M_PI / 2 + 1e-12);
  }
}

TEST(Se3, ExpInvertsLogUpToSign) {
  std::mt19937_64 rng(2);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Quaterniond q = random_quaternion(rng);
    const Eigen::Quaterniond back = quat_exp(quat_log(q));
    EXPECT_NEAR(std::abs(back.dot(q)), 1.0, 1e-12);
    EXPECT_TRUE(back.toRotationMatrix().isApprox(q.toRotationMatrix(), 1e-12));
  }
  EXPECT_TRUE(quat_exp(Eigen::Vector3d::Zero()).coeffs().isApprox(Eigen::Quaterniond::Identity().coeffs()));
}

TEST(Se3, ComposeAndInverseMatchHomogeneousMatrices) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> n;
  PoseArray a(20, 7), b(20, 7);
  std::vector<Eigen::Matrix4d> Ma, Mb;
  for (int i = 0; i < 20; ++i) {
    const Eigen::Quaterniond qa = random_quaternion(rng), qb = random_quaternion(rng);
    const Eigen::Vector3d ta(n(rng), n(rng), n(rng)), tb(n(rng), n(rng), n(rng));
    a.row(i) << ta.transpose(), qa.x(), qa.y(), qa.z(), qa.w();
    b.row(i) << tb.transpose(), qb.x(), qb.y(), qb.z(), qb.w();
    Eigen::Matrix4d A = Eigen::Matrix4d::Identity(), B = Eigen::Matrix4d::Identity();
    A.topLeftCorner<3, 3>() = qa.toRotationMatrix();
    A.topRightCorner<3, 1>() = ta;
    B.topLeftCorner<3, 3>() = qb.toRotationMatrix();
    B.topRightCorner<3, 1>() = tb;
    Ma.push_back(A);
    Mb.push_back(B);
  }
  const PoseArray ab = pose_multiply(a, b), ai = pose_inverse(a);
  for (int i = 0; i < 20; ++i) {
    EXPECT_TRUE(pose_from_vector(ab.row(i).transpose()).matrix().isApprox(Ma[i] * Mb[i], 1e-12));
    EXPECT_TRUE(pose_from_vector(ai.row(i).transpose()).matrix().isApprox(Ma[i].inverse(), 1e-12));
    EXPECT_GE(ab(i, 6), 0.0);
  }
}

TEST(Se3, BroadcastsASinglePose) {
  PoseArray a(1, 7), b(3, 7);
  a << 1, 0, 0, 0, 0, 0, 1;
  b.setZero();
  b.col(6).setOnes();
  const PoseArray ab = pose_multiply(a, b);
  ASSERT_EQ(ab.rows(), 3);
  EXPECT_TRUE(ab.col(0).isApprox(Eigen::Vector3d::Ones()));
}

TEST(Se3, BadInputThrowsNamingTheRow) {
  PoseArray a(2, 7);
  a.setZero();
  a(0, 6) = 1.0;  // row 1 has a zero quaternion
  try {
    pose_inverse(a);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("row 1"), std::string::npos) << e.what();
  }
  PoseArray b(2, 3 + 4), c(3, 7);
  b.setZero();
  b.col(6).setOnes();
  c = PoseArray::Zero(3, 7);
  EXPECT_THROW(pose_multiply(b, c), std::invalid_argument);
  Vec3Array w(1, 3);
  w << std::nan(""), 0, 0;
  EXPECT_THROW(batch_quat_exp(w), std::invalid_argument);
}
