// Constraint experts against analytic values.
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <random>

#include <gtest/gtest.h>

#include "graspmix/grasp/experts.hpp"

using namespace graspmix;
namespace fs = std::filesystem;

namespace {
const fs::path kRepo = GRASPMIX_SOURCE_DIR;  // set by CMakeLists.txt for the tests
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
  EXPECT_THROW(AxisAlignmentExpert(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ()), std::invalid_argument);
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

TEST(Experts, CollisionFreeIsTheCollisionExpertsVerdictAtTheGraspAndItsPregrasp) {
  const auto hand = wsg50();
  // A 6 cm cube of points centred 5 cm above a table; hands placed all around it, about half touching.
  Vec3Array cube(6 * 21 * 21, 3);
  Eigen::Index k = 0;
  for (int face = 0; face < 6; ++face)
    for (int i = 0; i < 21; ++i)
      for (int j = 0; j < 21; ++j) {
        Eigen::Vector3d p;
        const double u = -0.03 + 0.003 * i, v = -0.03 + 0.003 * j, s = face % 2 ? 0.03 : -0.03;
        p << (face / 2 == 0 ? s : u), (face / 2 == 1 ? s : (face / 2 == 0 ? u : v)), (face / 2 == 2 ? s : v);
        cube.row(k++) = (p + Eigen::Vector3d(0, 0, 0.05)).transpose();
      }
  const auto collision = std::make_shared<CollisionExpert>(hand, cube, Eigen::Vector4d(0, 0, 1, 0));
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1), open(0.0, 0.055);
  const int n = 400;
  PoseArray w(n, 7);
  RowMatrixXd q(n, 1);
  for (int i = 0; i < n; ++i) {
    Eigen::Quaterniond r(u(rng), u(rng), u(rng), u(rng));
    r.normalize();
    const Eigen::Vector3d approach = r * Eigen::Vector3d::UnitZ();  // the palm's z points at the cube
    const Eigen::Vector3d pos = Eigen::Vector3d(0, 0, 0.05) - approach * (0.15 + 0.08 * (u(rng) + 1) / 2);
    w.row(i) << pos.x(), pos.y(), pos.z(), r.x(), r.y(), r.z(), r.w();
    q(i, 0) = open(rng);
  }
  RowMatrixXd limits(1, 2);
  limits << 0.0, 0.055;
  const ConfigModel config(Eigen::VectorXd::Constant(1, 0.05), Eigen::VectorXd::Constant(1, 0.02), limits);
  RowMatrixXd pre(n, 1);
  for (int i = 0; i < n; ++i) pre.row(i) = config.pregrasp_for(q.row(i).transpose()).transpose();
  const auto at_grasp = collision->evaluate_batch(w, q).collision_free;
  const auto at_pre = collision->evaluate_batch(w, pre).collision_free;
  const Eigen::VectorXd with_pre = CollisionFreeExpert(collision, config).log_value({w, q});
  const Eigen::VectorXd grasp_only = CollisionFreeExpert(collision, std::nullopt).log_value({w, q});
  int rejected = 0, only_by_pregrasp = 0;
  for (int i = 0; i < n; ++i) {
    EXPECT_EQ(with_pre[i], at_grasp[i] && at_pre[i] ? 0.0 : -std::numeric_limits<double>::infinity()) << i;
    EXPECT_EQ(grasp_only[i], at_grasp[i] ? 0.0 : -std::numeric_limits<double>::infinity()) << i;
    rejected += !(at_grasp[i] && at_pre[i]);
    only_by_pregrasp += at_grasp[i] && !at_pre[i];
  }
  EXPECT_GT(rejected, n / 10);  // the cases are not all of one kind
  EXPECT_LT(rejected, n - n / 10);
  EXPECT_GT(only_by_pregrasp, 0);  // the opened hand is what hits
  const RowMatrixXd two_joints = RowMatrixXd::Zero(n, 2);
  EXPECT_THROW(CollisionFreeExpert(collision, config).log_value({w, two_joints}), std::invalid_argument);
  EXPECT_THROW(CollisionFreeExpert(nullptr, config), std::invalid_argument);
}
