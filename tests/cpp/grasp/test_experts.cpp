// Constraint experts against analytic values.
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>

#include <gtest/gtest.h>

#include "graspmix/grasp/experts.hpp"

using namespace graspmix;
namespace fs = std::filesystem;

namespace {
const fs::path kRepo = fs::path(__FILE__).parent_path().parent_path().parent_path().parent_path();  // tests/cpp/<layer>/x.cpp
std::shared_ptr<const Hand> wsg50() {
  return std::make_shared<Hand>(Hand::from_urdf((kRepo / "data" / "hands" / "wsg50.urdf").string()));
}
PoseArray wrist(double z, const Eigen::Quaterniond& q) {
  PoseArray w(1, 7);
  w << 0, 0, z, q.x(), q.y(), q.z(), q.w();
  return w;
}
}  // namespace

TEST(Experts, AxisAlignmentIsConcentrationTimesCosineMinusOne) {
  const AxisAlignmentExpert e(Eigen::Vector3d(0, 0, -1), Eigen::Vector3d::UnitZ(), 4.0);
  const RowMatrixXd q = RowMatrixXd::Constant(1, 1, 0.03);
  // Palm z down (rotation pi about x): aligned.
  EXPECT_NEAR(e.log_value({wrist(0.3, Eigen::Quaterniond(0, 1, 0, 0)), q})[0], 0.0, 1e-12);
  // Identity: palm z up, opposite.
  EXPECT_NEAR(e.log_value({wrist(0.3, Eigen::Quaterniond::Identity()), q})[0], -8.0, 1e-12);
  // Sideways: 90 degrees.
  const Eigen::Quaterniond side(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitX()));
  EXPECT_NEAR(e.log_value({wrist(0.3, side), q})[0], -4.0, 1e-12);
  EXPECT_THROW(AxisAlignmentExpert(Eigen::Vector3d::Zero()), std::invalid_argument);
}

TEST(Experts, KinematicFeasibilityRejectsLimitsPlaneAndUnreachable) {
  const auto hand = wsg50();
  const Eigen::Vector4d table(0, 0, 1, 0);
  const Eigen::Quaterniond down(0, 1, 0, 0);  // fingertips 0.1535 m below the flange
  PoseArray w(4, 7);
  w.row(0) = wrist(0.30, down).row(0);  // clear
  w.row(1) = wrist(0.30, down).row(0);  // joint beyond its limit
  w.row(2) = wrist(0.10, down).row(0);  // fingertips through the table
  w.row(3) = wrist(0.30, down).row(0);  // unreachable by the user's test
  RowMatrixXd q(4, 1);
  q << 0.03, 0.07, 0.03, 0.03;
  auto reachable = [](const PoseArray& wr, const RowMatrixXd&) {
    Eigen::Matrix<bool, Eigen::Dynamic, 1> ok(wr.rows());
    ok.setConstant(true);
    ok[3] = false;
    return ok;
  };
  const KinematicFeasibilityExpert e(hand, table, 0.0, reachable);
  const Eigen::VectorXd v = e.log_value({w, q});
  EXPECT_EQ(v[0], 0.0);
  for (int i = 1; i < 4; ++i) EXPECT_EQ(v[i], -std::numeric_limits<double>::infinity()) << i;
  // Without the plane, the low hand is fine.
  const KinematicFeasibilityExpert no_plane(hand);
  EXPECT_EQ(no_plane.log_value({w, q})[2], 0.0);
  auto wrong = [](const PoseArray&, const RowMatrixXd&) { return Eigen::Matrix<bool, Eigen::Dynamic, 1>(1); };
  const KinematicFeasibilityExpert bad(hand, std::nullopt, 0.0, wrong);
  EXPECT_THROW(bad.log_value({w, q}), std::invalid_argument);
}

TEST(Experts, FunctionExpertChecksWhatItGetsBack) {
  const PoseArray w = wrist(0.3, Eigen::Quaterniond::Identity());
  const RowMatrixXd q = RowMatrixXd::Zero(1, 1);
  const FunctionExpert ok("half", [](const PoseArray& wr, const RowMatrixXd&) {
    return Eigen::VectorXd::Constant(wr.rows(), std::log(0.5));
  });
  EXPECT_NEAR(ok.log_value({w, q})[0], std::log(0.5), 1e-15);
  const FunctionExpert nan("nan", [](const PoseArray& wr, const RowMatrixXd&) {
    return Eigen::VectorXd::Constant(wr.rows(), std::nan(""));
  });
  EXPECT_THROW(nan.log_value({w, q}), std::invalid_argument);
  const FunctionExpert size("size", [](const PoseArray&, const RowMatrixXd&) { return Eigen::VectorXd(3); });
  EXPECT_THROW(size.log_value({w, q}), std::invalid_argument);
}
